#include "semantic_edge_vo/backend/corner_tracks.h"

#include <opencv2/imgproc.hpp>
#include <opencv2/video/tracking.hpp>

namespace semantic_edge_vo {

std::vector<cv::Mat> CornerTracks::pyramid(const cv::Mat& gray) const {
  std::vector<cv::Mat> levels;
  cv::buildOpticalFlowPyramid(gray, levels, cv::Size(window_, window_), levels_, true);
  return levels;
}

void CornerTracks::reset(const cv::Mat& gray, const std::vector<cv::Point2f>& pixels) {
  previous_ = pyramid(gray);
  restart(pixels);
}

void CornerTracks::restart(const std::vector<cv::Point2f>& pixels) {
  first_ = pixels;
  current_ = pixels;
  ids_.resize(pixels.size());
  for (std::size_t i = 0; i < pixels.size(); ++i) ids_[i] = static_cast<int>(i);
  frames_ = 0;
}

std::size_t CornerTracks::track(const cv::Mat& gray) {
  ++frames_;
  std::vector<cv::Mat> levels = pyramid(gray);
  if (current_.empty()) {  // OpenCV's KLT throws on an empty point set
    previous_ = std::move(levels);
    return 0;
  }
  std::vector<cv::Point2f> next, back;
  std::vector<std::uint8_t> status, back_status;
  std::vector<float> error;
  const cv::Size window(window_, window_);
  cv::calcOpticalFlowPyrLK(previous_, levels, current_, next, status, error, window, levels_);
  cv::calcOpticalFlowPyrLK(levels, previous_, next, back, back_status, error, window, levels_);
  std::size_t kept = 0;
  for (std::size_t i = 0; i < current_.size(); ++i) {
    const bool inside = next[i].x >= 0 && next[i].y >= 0 && next[i].x < gray.cols && next[i].y < gray.rows;
    if (!status[i] || !back_status[i] || !inside || cv::norm(back[i] - current_[i]) > 0.5) continue;
    first_[kept] = first_[i];
    current_[kept] = next[i];
    ids_[kept] = ids_[i];
    ++kept;
  }
  first_.resize(kept);
  current_.resize(kept);
  ids_.resize(kept);
  previous_ = std::move(levels);
  return kept;
}

std::vector<cv::Point2f> detectCorners(const cv::Mat& gray, int count, double min_distance) {
  if (gray.cols < 2 || gray.rows < 2 || count <= 0) return {};
  cv::Mat half;
  cv::resize(gray, half, cv::Size(gray.cols / 2, gray.rows / 2), 0, 0, cv::INTER_AREA);
  std::vector<cv::Point2f> corners;
  cv::goodFeaturesToTrack(half, corners, count, 0.01, 0.5 * min_distance);
  // Pixel centres: half-resolution pixel x covers full-resolution pixels 2x and 2x + 1.
  for (cv::Point2f& corner : corners) corner = 2.0f * corner + cv::Point2f(0.5f, 0.5f);
  return corners;
}

}  // namespace semantic_edge_vo
