#pragma once
#include <algorithm>
#include <cstddef>
#include <vector>

#include <opencv2/core/mat.hpp>

namespace semantic_edge_vo {

/// Points followed frame to frame with pyramidal Lucas-Kanade and a forward-backward check: a point
/// is dropped when it is lost, leaves the image, or does not come back to within 0.5 px.
class CornerTracks {
 public:
  /// @param window KLT window side, px; @param levels KLT pyramid levels above full resolution
  explicit CornerTracks(int window = 21, int levels = 3) : window_(std::max(window, 3)), levels_(std::max(levels, 0)) {}

  /// Starts tracks at `pixels` of `gray` (CV_8UC1).
  void reset(const cv::Mat& gray, const std::vector<cv::Point2f>& pixels);
  /// Starts tracks at `pixels` of the frame last given (to reset() or track()), whose pyramid is kept.
  void restart(const std::vector<cv::Point2f>& pixels);
  /// Follows the tracks into the next frame (CV_8UC1). Returns the number kept.
  std::size_t track(const cv::Mat& gray);

  const std::vector<cv::Point2f>& first() const { return first_; }      ///< where each track started
  const std::vector<cv::Point2f>& current() const { return current_; }  ///< where it is in the last frame
  const std::vector<int>& ids() const { return ids_; }                  ///< index of each track in the pixels it started from
  int framesTracked() const { return frames_; }                         ///< track() calls since reset() or restart()

 private:
  std::vector<cv::Mat> pyramid(const cv::Mat& gray) const;

  int window_, levels_;
  std::vector<cv::Mat> previous_;  ///< KLT pyramid of the last frame
  std::vector<cv::Point2f> first_, current_;
  std::vector<int> ids_;
  int frames_ = 0;
};

/// Up to `count` Shi-Tomasi corners of `gray`, at least `min_distance` px apart, detected at half
/// resolution (a quarter of the cost; where a track starts needs no sub-pixel precision, KLT follows
/// the patch there) and returned in full-resolution pixels.
std::vector<cv::Point2f> detectCorners(const cv::Mat& gray, int count, double min_distance);

}  // namespace semantic_edge_vo
