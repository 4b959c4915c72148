#include "semantic_edge_vo/frontend/motion_model.h"

#include <algorithm>
#include <cmath>

#include "semantic_edge_vo/common/robust_statistics.h"

namespace semantic_edge_vo {
void MotionModel::remember(const Eigen::Isometry3d& T_world_cam, const FrameStamp& stamp, bool trusted,
                           const Eigen::Isometry3d& window_correction) {
  T_world_before_ = T_world_last_;
  T_world_last_ = orthonormalized(T_world_cam);
  last_window_correction_ = window_correction;
  before_stamp_ = last_stamp_;
  last_stamp_ = stamp;
  if (trusted) last_trusted_stamp_ = last_stamp_;
  ++poses_seen_;
  const int indices = last_stamp_.index - before_stamp_.index;
  const double seconds = last_stamp_.time - before_stamp_.time;
  if (poses_seen_ >= 2 && indices > 0 && seconds > 0.0) keepLast(seconds / indices, kFrameIntervals, &frame_intervals_);
  if (!trusted || poses_seen_ < 2) return;
  // Only motions of a driving camera are kept: the store outlasts a stop of any length.
  Vector6d motion = se3Log(frameMotion());
  if (motion.head<3>().norm() < kStandingFraction * drivingMotion().head<3>().norm()) return;
  motion.tail<3>().setZero();  // the travel; a turn it made then says nothing of the start
  keepLast(motion, kDrivingMotions, &driving_motions_);
}

void MotionModel::correct(const Eigen::Isometry3d& correction) {
  T_world_last_ = orthonormalized(correction * T_world_last_);
  T_world_before_ = orthonormalized(correction * T_world_before_);
}

void MotionModel::rescale(double scale, const Eigen::Vector3d& about) {
  scaleAbout(scale, about, &T_world_last_);
  scaleAbout(scale, about, &T_world_before_);
  for (Vector6d& motion : driving_motions_) motion.head<3>() *= scale;  // pure travel: its log is the translation
}

double MotionModel::framesBetween(const FrameStamp& from, const FrameStamp& to) const {
  const double interval = median({frame_intervals_.begin(), frame_intervals_.end()});
  const double frames = interval > 0.0 ? (to.time - from.time) / interval : static_cast<double>(to.index - from.index);
  return frames >= 1.0 ? std::round(frames) : 1.0;  // also 1 for a stamp that is not a number
}

double MotionModel::framesToExtrapolate(const FrameStamp& frame) const {
  // Dead reckoning ends kMaxDeadReckoning frames after the last trusted pose: the car may have
  // stopped since (a loss it never finds its map again from would otherwise drive on for ever).
  const double since_trusted = last_stamp_.index == last_trusted_stamp_.index ? 0.0 : framesBetween(last_trusted_stamp_, last_stamp_);
  const double left = std::max(0.0, static_cast<double>(kMaxDeadReckoning) - since_trusted);
  return std::min(framesBetween(last_stamp_, frame), left);
}

Eigen::Isometry3d MotionModel::perFrame(const Eigen::Isometry3d& motion) const {
  const double frames = framesBetween(before_stamp_, last_stamp_);
  return frames == 1.0 ? motion : se3Exp(se3Log(motion) / frames);  // frames dropped between them: the mean
}

Eigen::Isometry3d MotionModel::frameMotion() const {
  if (poses_seen_ < 2) return Eigen::Isometry3d::Identity();
  return perFrame(T_world_before_.inverse() * T_world_last_);
}

Eigen::Isometry3d MotionModel::extrapolate(const Eigen::Isometry3d& per_frame, const FrameStamp& frame) const {
  const double frames = framesToExtrapolate(frame);
  if (frames == 1.0) return T_world_last_ * per_frame;
  return T_world_last_ * se3Exp(frames * se3Log(per_frame));
}

Eigen::Isometry3d MotionModel::predict(const FrameStamp& frame) const { return extrapolate(frameMotion(), frame); }

Eigen::Isometry3d MotionModel::predictAtTrackedVelocity(const FrameStamp& frame) const {
  if (poses_seen_ < 2) return T_world_last_;
  return extrapolate(perFrame(T_world_before_.inverse() * last_window_correction_.inverse() * T_world_last_), frame);
}

Vector6d MotionModel::drivingMotion(std::size_t newest) const {
  if (driving_motions_.empty()) return Vector6d::Zero();
  // The median by length: one jump (dropped frames, a correction) does not make it.
  std::vector<const Vector6d*> sorted;
  for (auto motion = driving_motions_.end() - static_cast<std::ptrdiff_t>(std::min(newest, driving_motions_.size()));
       motion != driving_motions_.end(); ++motion)
    sorted.push_back(&*motion);
  std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(sorted.size() / 2), sorted.end(),
                   [](const Vector6d* a, const Vector6d* b) { return a->head<3>().norm() < b->head<3>().norm(); });
  return *sorted[sorted.size() / 2];
}

std::vector<Eigen::Isometry3d> MotionModel::guesses(const FrameStamp& frame) const {
  if (poses_seen_ < 2) return {T_world_last_};
  const Vector6d velocity = se3Log(frameMotion());
  const double n = framesToExtrapolate(frame);
  // Constant velocity first, then no motion, half and double the velocity.
  std::vector<Eigen::Isometry3d> world_poses = {T_world_last_ * se3Exp(n * velocity), T_world_last_,
                                                T_world_last_ * se3Exp(0.5 * n * velocity), T_world_last_ * se3Exp(2.0 * n * velocity)};
  // Standing, or nearly: the guesses above all say "no motion". A car drives off the way it came:
  // one frame's travel at the speed it drove at before is one more (a start that the frames caught
  // late, or dropped; not times the frames missed: a car starting from rest covers less).
  const Vector6d driving = drivingMotion();
  if (velocity.head<3>().norm() < kStandingFraction * driving.head<3>().norm()) world_poses.push_back(T_world_last_ * se3Exp(driving));
  return world_poses;
}

}  // namespace semantic_edge_vo
