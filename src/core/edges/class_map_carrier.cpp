#include "semantic_edge_vo/edges/class_map_carrier.h"

#include <algorithm>
#include <sstream>

#include <opencv2/imgproc.hpp>
#include <opencv2/video/tracking.hpp>

namespace semantic_edge_vo {

namespace {

/// Each pixel's own coordinates, CV_32FC2.
cv::Mat pixelGrid(cv::Size size) {
  cv::Mat grid(size, CV_32FC2);
  for (int y = 0; y < size.height; ++y) {
    cv::Vec2f* row = grid.ptr<cv::Vec2f>(y);
    for (int x = 0; x < size.width; ++x) row[x] = cv::Vec2f(static_cast<float>(x), static_cast<float>(y));
  }
  return grid;
}

}  // namespace

std::string ClassMapCarrierOptions::validate() const {
  std::ostringstream error;
  if (!(flow_scale > 0.0 && flow_scale <= 1.0)) error << "flow_scale must be in (0, 1] (got " << flow_scale << ")";
  else if (!(max_age > 0.0)) error << "max_age must be > 0 s (got " << max_age << ")";
  else if (remembered_images < 1) error << "remembered_images must be >= 1 (got " << remembered_images << ")";
  else if (!(max_loop_error > 0.0)) error << "max_loop_error must be > 0 px (got " << max_loop_error << ")";
  return error.str();
}

ClassMapCarrier::ClassMapCarrier(const ClassMapCarrierOptions& options)
    : options_(options), flow_(cv::DISOpticalFlow::create(cv::DISOpticalFlow::PRESET_FAST)) {}
ClassMapCarrier::~ClassMapCarrier() = default;
ClassMapCarrier::ClassMapCarrier(ClassMapCarrier&&) noexcept = default;
ClassMapCarrier& ClassMapCarrier::operator=(ClassMapCarrier&&) noexcept = default;

void ClassMapCarrier::addImage(double time, const cv::Mat& gray) {
  RememberedImage image{time, cv::Mat()};
  if (options_.flow_scale == 1.0) image.small = gray.clone();
  else cv::resize(gray, image.small, cv::Size(), options_.flow_scale, options_.flow_scale, cv::INTER_AREA);
  images_.push_back(std::move(image));
  while (static_cast<int>(images_.size()) > options_.remembered_images) images_.pop_front();
  if (has_map_) measurePositions();
}

void ClassMapCarrier::measurePositions() {
  const cv::Mat& newest = images_.back().small;
  if (newest.size() != map_image_.size()) {  // a new image size: the map says nothing of it
    has_map_ = false;
    return;
  }
  cv::Mat back, forth, returned;
  flow_->calc(newest, map_image_, back);
  flow_->calc(map_image_, newest, forth);
  positions_ = pixelGrid(newest.size()) + back;
  // Forward-backward check: where the flow back and then forth does not return to the pixel (the
  // repeated windows of a facade, occlusions), the pixel keeps its own place, the stale map's
  // class, rather than a wrong class from far away.
  cv::remap(forth, returned, positions_, cv::noArray(), cv::INTER_LINEAR, cv::BORDER_REPLICATE);
  const float limit = static_cast<float>(options_.max_loop_error * options_.flow_scale);
  for (int y = 0; y < positions_.rows; ++y) {
    cv::Vec2f* position = positions_.ptr<cv::Vec2f>(y);
    const cv::Vec2f* b = back.ptr<cv::Vec2f>(y);
    const cv::Vec2f* r = returned.ptr<cv::Vec2f>(y);
    for (int x = 0; x < positions_.cols; ++x) {
      const cv::Vec2f loop = b[x] + r[x];
      if (loop.dot(loop) > limit * limit) position[x] = cv::Vec2f(static_cast<float>(x), static_cast<float>(y));
    }
  }
}

bool ClassMapCarrier::setClassMap(double time, const ClassEvidence& evidence) {
  if (has_map_ && time <= map_time_) return false;
  const auto image = std::find_if(images_.begin(), images_.end(), [&](const RememberedImage& i) { return i.time == time; });
  if (image == images_.end()) return false;
  map_ = evidence;
  map_.values = evidence.values.clone();
  map_time_ = time;
  map_image_ = image->small;
  has_map_ = true;
  if (time != images_.back().time) measurePositions();
  return has_map_;
}

bool ClassMapCarrier::carryTo(double time, ClassEvidence* carried, double* age) const {
  if (!has_map_ || images_.empty() || time != images_.back().time || time - map_time_ > options_.max_age) return false;
  *age = time - map_time_;
  *carried = map_;
  if (time == map_time_) return true;
  // Positions from the flow's scale to the map's: pixel centres map to pixel centres.
  cv::Mat positions;
  cv::resize(positions_, positions, map_.values.size(), 0.0, 0.0, cv::INTER_LINEAR);
  const double to_map = static_cast<double>(map_.values.cols) / positions_.cols;
  positions.convertTo(positions, CV_32FC2, to_map, 0.5 * to_map - 0.5);
  // Nearest: class indices and bits are not blended.
  cv::remap(map_.values, carried->values, positions, cv::noArray(), cv::INTER_NEAREST, cv::BORDER_REPLICATE);
  return true;
}

void ClassMapCarrier::clear() {
  images_.clear();
  has_map_ = false;
  map_ = ClassEvidence();
  map_image_.release();
  positions_.release();
}

}  // namespace semantic_edge_vo
