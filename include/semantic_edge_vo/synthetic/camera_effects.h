#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include <opencv2/core/mat.hpp>

namespace semantic_edge_vo {
namespace synthetic {

/// What the sensor does to the light: auto-exposure drift, vignetting, noise.
struct CameraEffectsOptions {
  double exposure_variation = 0.25;  ///< amplitude of the log exposure gain drift (0: fixed exposure)
  double exposure_period = 12.0;     ///< time scale of the drift, s (a faster drift of a quarter of it rides on top)
  double vignetting = 0.35;          ///< brightness lost in the image corners, fraction
  double read_noise = 1.5;           ///< Gaussian noise, gray levels (standard deviation)
  double shot_noise = 0.05;          ///< signal-dependent noise variance, gray levels per gray level

  std::string validate() const;
};

/// Turns radiance into 8-bit images, deterministically for a seed and frame.
class CameraEffects {
 public:
  CameraEffects(const CameraEffectsOptions& options, int width, int height, std::uint64_t seed);

  /// Exposure gain at `time` (s): 255 times a slowly drifting factor.
  double exposureGain(double time) const;
  /// Colour (CV_8UC3, BGR) and grayscale (CV_8UC1, luma of the same light) of `radiance` (CV_32FC3).
  void expose(const cv::Mat& radiance, double time, int frame, cv::Mat* color, cv::Mat* gray) const;

 private:
  CameraEffectsOptions options_;
  std::uint64_t seed_;
  cv::Mat vignette_;           // CV_32FC1 gain per pixel
  std::vector<float> normal_;  // a table of standard normal numbers, read at a random place per frame
};

}  // namespace synthetic
}  // namespace semantic_edge_vo
