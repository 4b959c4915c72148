#include "semantic_edge_vo/backend/keyframe_motion.h"

#include <algorithm>
#include <cmath>

#include "semantic_edge_vo/common/robust_statistics.h"
#include "semantic_edge_vo/common/se3.h"
#include "semantic_edge_vo/backend/two_view_geometry.h"

namespace semantic_edge_vo {
namespace {

double radians(double degrees) { return degrees * M_PI / 180.0; }

/// Median distance of the inlier corners from where the rotation alone would have moved them, px.
double medianParallax(const std::vector<cv::Point2f>& first, const std::vector<cv::Point2f>& second, const TwoViewMotion& motion,
                      const PinholeCamera& camera) {
  std::vector<double> parallax;
  for (std::size_t i = 0; i < first.size(); ++i) {
    if (!motion.inliers[i]) continue;
    const Eigen::Vector3d turned = motion.R_second_first * camera.backProject(first[i].x, first[i].y, 1.0);
    if (turned.z() <= 0.0) continue;
    parallax.push_back((camera.project(turned) - Eigen::Vector2d(second[i].x, second[i].y)).norm());
  }
  return parallax.empty() ? 0.0 : median(parallax);
}

/// Sideways angle (about the optical y axis) from the vehicle's chord, forward or reversed, to the
/// measured direction of travel, rad.
double lateralDeviation(const TwoViewMotion& motion, const ForwardMotionOptions& forward) {
  const Eigen::Matrix3d R_first_second = motion.R_second_first.transpose();
  const Eigen::Vector3d direction = -(R_first_second * motion.t_second_first);
  Eigen::Vector3d chord = forward.chord(R_first_second);
  if (chord.dot(direction) < 0.0) chord = -chord;  // reversing
  return std::remainder(std::atan2(direction.x(), direction.z()) - std::atan2(chord.x(), chord.z()), 2.0 * M_PI);
}

}  // namespace

std::string KeyframeMotionOptions::validate() const {
  if (corners < 0 || window < 3 || min_inliers < 5) return "keyframe_motion: need corners >= 0, window >= 3 px, min_inliers >= 5";
  if (!(min_distance >= 0 && ransac_threshold > 0 && min_parallax >= 0))
    return "keyframe_motion: min_distance and min_parallax must be >= 0 px, ransac_threshold > 0 px";
  if (!(max_chord_deviation_deg >= 0)) return "keyframe_motion: max_chord_deviation must be >= 0 deg (0: off)";
  if (!(reanchor_rotation_deg > 0 && reanchor_direction_deg > 0 && reanchor_max_rotation_deg >= reanchor_rotation_deg &&
        reanchor_max_direction_deg >= reanchor_direction_deg))
    return "keyframe_motion: need 0 < reanchor_rotation <= reanchor_max_rotation and 0 < reanchor_direction <= reanchor_max_direction (deg)";
  return "";
}

KeyframeMotion::KeyframeMotion(const KeyframeMotionOptions& options, const PinholeCamera& camera)
    : options_(options), camera_(camera), tracks_(options.window) {}

void KeyframeMotion::start(int keyframe_id, int frame_index, const cv::Mat& gray) {
  if (!enabled()) return;
  const std::vector<cv::Point2f> corners = detectCorners(gray, options_.corners, options_.min_distance);
  // A keyframe is a tracked frame: its pyramid is already built when the corners followed into it.
  if (frame_index == frame_index_) tracks_.restart(corners);
  else tracks_.reset(gray, corners);
  keyframe_id_ = keyframe_id;
  frame_index_ = frame_index;
}

void KeyframeMotion::follow(int frame_index, const cv::Mat& gray) {
  if (!enabled() || keyframe_id_ < 0) return;
  tracks_.track(gray);
  frame_index_ = frame_index;
}

MeasuredMotion KeyframeMotion::measure(int frame_index, const Eigen::Matrix3d& R_from_this_guess) const {
  MeasuredMotion measured;
  if (!enabled() || keyframe_id_ < 0 || frame_index != frame_index_ || tracks_.framesTracked() == 0) return measured;
  const std::vector<cv::Point2f>& first = tracks_.first();
  const std::vector<cv::Point2f>& current = tracks_.current();
  TwoViewMotion motion;
  const bool vehicle = options_.max_chord_deviation_deg > 0.0 && options_.forward_motion.sigma_deg > 0.0;
  bool found = estimateTwoViewMotion(first, current, camera_, options_.ransac_threshold, options_.min_inliers, &motion) &&
               medianParallax(first, current, motion, camera_) >= options_.min_parallax;
  if (found && vehicle) found = std::abs(lateralDeviation(motion, options_.forward_motion)) <= radians(options_.max_chord_deviation_deg);
  // Off the chord, or not measured at all (too few corners agree with five free dimensions, or too
  // little parallax for them): the rotation alone, with the travel the vehicle allows.
  if (!found && vehicle)
    found = estimateVehicleMotion(first, current, camera_, options_.forward_motion, options_.ransac_threshold, options_.min_inliers,
                                  R_from_this_guess.transpose(), &motion) &&
            medianParallax(first, current, motion, camera_) >= options_.min_parallax;
  if (!found) return measured;
  measured.from_id = keyframe_id_;
  measured.R_from_this = motion.R_second_first.transpose();
  measured.direction = -(measured.R_from_this * motion.t_second_first).normalized();  // the second centre, -R^T t
  return measured;
}

bool reanchor(const MeasuredMotion& measured, const KeyframeMotionOptions& options, const Eigen::Isometry3d& T_world_earlier,
              Eigen::Isometry3d* T_world_new) {
  Eigen::Isometry3d T_earlier_new = T_world_earlier.inverse() * *T_world_new;
  const double distance = T_earlier_new.translation().norm();
  if (measured.from_id < 0 || !(distance > 0.0)) return false;
  const double rotation_off = Eigen::AngleAxisd(measured.R_from_this.transpose() * T_earlier_new.linear()).angle();
  const double direction_off = std::acos(std::clamp(T_earlier_new.translation().dot(measured.direction) / distance, -1.0, 1.0));
  if (rotation_off <= radians(options.reanchor_rotation_deg) && direction_off <= radians(options.reanchor_direction_deg)) return false;
  if (rotation_off > radians(options.reanchor_max_rotation_deg) || direction_off > radians(options.reanchor_max_direction_deg)) return false;
  T_earlier_new.linear() = measured.R_from_this;
  T_earlier_new.translation() = distance * measured.direction;
  *T_world_new = orthonormalized(T_world_earlier * T_earlier_new);
  return true;
}

}  // namespace semantic_edge_vo
