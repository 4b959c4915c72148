#pragma once
#include <vector>

#include <opencv2/core/mat.hpp>

#include "semantic_edge_vo/common/camera.h"

namespace semantic_edge_vo {

/// One level of a frame's pyramid. The photometric channel is the image-gradient magnitude
/// (paper III-C: robust to illumination changes), with its own derivatives for the Jacobians.
struct PyramidLevel {
  PinholeCamera camera;    ///< intrinsics of this level
  cv::Mat intensity;       ///< CV_32FC1, gray levels (2x2 area averages of the level below)
  cv::Mat gradient;        ///< CV_32FC1, gradient magnitude of `intensity`, gray levels / px
  cv::Mat gradient_dx;     ///< CV_32FC1, d gradient / du
  cv::Mat gradient_dy;     ///< CV_32FC1, d gradient / dv
};

/// Levels 0 (full resolution) to levels-1, each half the size of the one below; coordinates follow
/// the pixel-centre convention of `toLevel` (nearest_neighbor_field.h).
class ImagePyramid {
 public:
  /// @param[in] gray CV_8UC1 image of `camera`'s size
  ImagePyramid(const cv::Mat& gray, const PinholeCamera& camera, int levels);

  int levels() const { return static_cast<int>(levels_.size()); }
  const PyramidLevel& level(int l) const { return levels_[static_cast<std::size_t>(l)]; }

 private:
  std::vector<PyramidLevel> levels_;
};

/// Bilinear sample of a CV_32FC1 image; (x, y) must lie in [0, cols-1) x [0, rows-1).
inline float sampleBilinear(const cv::Mat& image, float x, float y) {
  const int x0 = static_cast<int>(x), y0 = static_cast<int>(y);
  const float ax = x - static_cast<float>(x0), ay = y - static_cast<float>(y0);
  // ptr() of both rows: cv::Mat::step1() is not inlined, and this runs millions of times a frame.
  const float* row0 = image.ptr<float>(y0);
  const float* row1 = image.ptr<float>(y0 + 1);
  return (1.0f - ay) * ((1.0f - ax) * row0[x0] + ax * row0[x0 + 1]) + ay * ((1.0f - ax) * row1[x0] + ax * row1[x0 + 1]);
}

}  // namespace semantic_edge_vo
