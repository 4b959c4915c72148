#include "semantic_edge_vo/common/robust_statistics.h"
#include "semantic_edge_vo/backend/two_view_initializer.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "semantic_edge_vo/backend/two_view_geometry.h"

namespace semantic_edge_vo {

std::string InitializerOptions::validate() const {
  std::ostringstream error;
  if (!(min_parallax > 0 && min_parallax < 1)) error << "min_parallax must be in (0, 1) (a fraction of the image width)";
  else if (max_frames < 1 || min_points < 8) error << "need max_frames >= 1 and min_points >= 8";
  else if (!(ransac_threshold > 0 && min_triangulation_angle >= 0 && median_depth > 0))
    error << "ransac_threshold and median_depth must be > 0, min_triangulation_angle >= 0";
  else if (!(max_travel_off_axis > 0 && max_travel_off_axis <= 180)) error << "max_travel_off_axis must be in (0, 180] deg";
  return error.str();
}

void TwoViewInitializer::reset(const cv::Mat& gray, const std::vector<Eigen::Vector2f>& pixels,
                               const Eigen::Vector3d& expected_travel) {
  expected_travel_ = expected_travel;
  std::vector<cv::Point2f> points;
  for (const Eigen::Vector2f& pixel : pixels) points.emplace_back(pixel.x(), pixel.y());
  tracks_.reset(gray, points);
  pixel_count_ = pixels.size();
  inverse_depths_.clear();
}

TwoViewInitializer::Status TwoViewInitializer::add(const cv::Mat& gray) {
  // Nothing to follow (a frame without candidates: all of it movable, say) fails too.
  const std::size_t kept = tracks_.track(gray);
  if (static_cast<int>(kept) < options_.min_points) return Status::kFailed;
  const std::vector<cv::Point2f>& first = tracks_.first();
  const std::vector<cv::Point2f>& current = tracks_.current();

  std::vector<double> flow;
  for (std::size_t i = 0; i < kept; ++i) flow.push_back(cv::norm(current[i] - first[i]));
  const bool last_chance = tracks_.framesTracked() >= options_.max_frames;
  if (median(flow) < options_.min_parallax * camera_.width && !last_chance) return Status::kNeedMoreFrames;
  if (solve()) return Status::kReady;
  return last_chance ? Status::kFailed : Status::kNeedMoreFrames;
}

bool TwoViewInitializer::solve() {
  const std::vector<cv::Point2f>& first = tracks_.first();
  const std::vector<cv::Point2f>& current = tracks_.current();
  TwoViewMotion motion;
  if (!estimateMotion(&motion)) return false;
  const Eigen::Matrix3d& R = motion.R_second_first;
  const Eigen::Vector3d& t = motion.t_second_first;

  // Depth d of each inlier in the first frame: the ray d * r0, moved by (R, t), must lie on the ray
  // through the pixel in the last frame: [x1]_x (d R r0 + t) = 0, solved in the least-squares sense.
  std::vector<double> depths(first.size(), 0.0), valid;
  const double min_angle = options_.min_triangulation_angle * M_PI / 180.0;
  for (std::size_t i = 0; i < first.size(); ++i) {
    if (!motion.inliers[i]) continue;
    const Eigen::Vector3d r0 = camera_.backProject(first[i].x, first[i].y, 1.0);
    const Eigen::Vector3d x1 = camera_.backProject(current[i].x, current[i].y, 1.0);
    const Eigen::Vector3d a = x1.cross(R * r0), b = x1.cross(t);
    const double d = -a.dot(b) / a.squaredNorm();
    if (!(d > 0.0) || !std::isfinite(d)) continue;
    const Eigen::Vector3d seen_from_last = d * (R * r0) + t;  // the point in the last frame
    const double angle = std::acos(std::clamp(seen_from_last.normalized().dot((R * r0).normalized()), -1.0, 1.0));
    if (seen_from_last.z() <= 0.0 || angle < min_angle) continue;
    depths[i] = d;
    valid.push_back(d);
  }
  if (static_cast<int>(valid.size()) < options_.min_points) return false;
  const double scale = options_.median_depth / median(valid);
  inverse_depths_.assign(pixel_count_, 0.0);
  for (std::size_t i = 0; i < first.size(); ++i)
    if (depths[i] > 0.0) inverse_depths_[static_cast<std::size_t>(tracks_.ids()[i])] = 1.0 / (depths[i] * scale);
  T_last_first_ = Eigen::Isometry3d::Identity();
  T_last_first_.linear() = R;
  T_last_first_.translation() = t * scale;
  return true;
}

bool TwoViewInitializer::travelsAsExpected(const TwoViewMotion& motion) const {
  if (expected_travel_.isZero()) return true;
  // The last camera's centre in the first one's frame.
  const Eigen::Vector3d travel = -motion.R_second_first.transpose() * motion.t_second_first;
  const double cosine = travel.normalized().dot(expected_travel_.normalized());
  return cosine >= std::cos(options_.max_travel_off_axis * M_PI / 180.0);
}

bool TwoViewInitializer::estimateMotion(TwoViewMotion* motion) const {
  const std::vector<cv::Point2f>& first = tracks_.first();
  const std::vector<cv::Point2f>& current = tracks_.current();
  if (!estimateTwoViewMotion(first, current, camera_, options_.ransac_threshold, options_.min_points, motion)) return false;
  if (travelsAsExpected(*motion)) return true;
  std::vector<cv::Point2f> first_rest, current_rest;
  std::vector<std::size_t> rest;
  for (std::size_t i = 0; i < first.size(); ++i) {
    if (motion->inliers[i]) continue;
    first_rest.push_back(first[i]);
    current_rest.push_back(current[i]);
    rest.push_back(i);
  }
  TwoViewMotion other;
  if (!estimateTwoViewMotion(first_rest, current_rest, camera_, options_.ransac_threshold, options_.min_points, &other) ||
      !travelsAsExpected(other))
    return false;
  motion->R_second_first = other.R_second_first;
  motion->t_second_first = other.t_second_first;
  motion->inlier_count = other.inlier_count;
  motion->inliers.assign(first.size(), 0);
  for (std::size_t j = 0; j < rest.size(); ++j) motion->inliers[rest[j]] = other.inliers[j];
  return true;
}

}  // namespace semantic_edge_vo
