// Odometry: the two-view initialisation, the first keyframe and the frames that waited for it.
#include <chrono>
#include <cmath>

#include "odometry_detail.h"
#include "semantic_edge_vo/backend/odometry.h"
#include "semantic_edge_vo/common/freed_memory.h"

namespace semantic_edge_vo {

using odometry_detail::elapsedMs;
using odometry_detail::gray8;

void Odometry::startInitialization(const std::shared_ptr<const OdometryFrame>& frame) {
  const auto start = std::chrono::steady_clock::now();
  waiting_ = {{frame, 0.0}};
  std::vector<Eigen::Vector2f> pixels;
  for (const MapPoint& point : frame->candidates) pixels.emplace_back(point.u, point.v);
  // A loss on a car is mostly traffic filling the view, and the largest consensus of the next frames
  // may be its motion: the new map must travel forward (not the estimate before the loss: traffic
  // may have dragged it off already).
  const ForwardMotionOptions& forward = options_.tracker.forward_motion;
  initializer_.reset(gray8(*frame), pixels, recovering_ && forward.sigma_deg > 0.0 ? forward.axis() : Eigen::Vector3d::Zero());
  waiting_.front().ms = elapsedMs(start);
}

std::vector<FramePose> Odometry::initialize(const std::shared_ptr<const OdometryFrame>& frame,
                                            std::chrono::steady_clock::time_point start) {
  state_ = OdometryState::kInitializing;
  if (waiting_.empty()) {
    startInitialization(frame);
    waiting_.front().ms = elapsedMs(start);
    return {};
  }
  const TwoViewInitializer::Status status = initializer_.add(gray8(*frame));
  waiting_.push_back({frame, elapsedMs(start)});
  if (status == TwoViewInitializer::Status::kNeedMoreFrames) return {};
  if (status == TwoViewInitializer::Status::kFailed) {
    // The waiting frames get untrusted predictions; the newest starts the next attempt.
    const WaitingFrame newest = waiting_.back();
    waiting_.pop_back();
    std::vector<FramePose> poses = flush();
    for (const FramePose& pose : poses) remember(pose);
    startInitialization(newest.frame);
    waiting_.front().ms += newest.ms;
    return poses;
  }
  const auto keyframe_start = std::chrono::steady_clock::now();
  Eigen::Isometry3d T_last_first;
  makeFirstKeyframe(&T_last_first);
  return posesOfWaitingFrames(T_last_first, elapsedMs(keyframe_start));
}

void Odometry::makeFirstKeyframe(Eigen::Isometry3d* T_last_first_out) {
  // The first waiting frame becomes the first keyframe, anchored where the odometry predicts it
  // (identity at the very start), so that odom stays continuous after a loss.
  Eigen::Isometry3d T_last_first = initializer_.T_last_first();
  double depth_scale = 1.0;
  bool scale_carried = false;
  if (recovering_ && motion_.posesSeen() >= 2) {
    const double speed = speed_at_restart_;  // per frame interval
    const double baseline = T_last_first.translation().norm();
    scale_carried = speed > 0.0 && baseline > 0.0;
    if (scale_carried) depth_scale = speed * motion_.framesBetween(stampOf(*waiting_.front().frame), stampOf(*waiting_.back().frame)) / baseline;
  }
  if (!scale_carried) motion_.forgetDrivingMotions();  // travel at another map's scale
  // A new map is in metres only as far as the old one's were carried into it, until its own road.
  if (!scale_carried) map_scale_measured_ = false;
  scale_ = map_scale_measured_ ? ScaleState::kHeld : ScaleState::kArbitrary;
  if (!map_scale_measured_) scale_confidence_ = 0.0;
  T_last_first.translation() *= depth_scale;
  const Eigen::Isometry3d T_world_first = motion_.predict(stampOf(*waiting_.front().frame));

  std::vector<double> inverse_depths = initializer_.inverseDepths();
  for (double& inverse_depth : inverse_depths) inverse_depth /= depth_scale;
  // Mapping finishes the old map's frames first (parallel mode: their outcomes are taken here).
  finishMapping();
  MappingRequest request;
  request.frame = waiting_.front().frame;
  request.new_map = true;
  request.T_world_cam = T_world_first;
  request.inverse_depths = std::move(inverse_depths);
  MappingOutcome outcome = mapNow(std::move(request));
  trackAgainst(outcome.active);
  new_windows_.push_back(outcome.window);
  *T_last_first_out = T_last_first;
}

std::vector<FramePose> Odometry::posesOfWaitingFrames(Eigen::Isometry3d T_last_first, double keyframe_ms) {
  const std::shared_ptr<const Keyframe> keyframe = keyframe_;  // tracking moves on to its refined copies
  const int keyframe_id = keyframe->id;
  const Eigen::Isometry3d& T_world_first = keyframe->T_world_cam;
  std::vector<FramePose> poses;
  FramePose first;
  first.index = keyframe->frame->index;
  first.time = keyframe->frame->time;
  first.T_world_cam = T_world_first;
  first.trusted = true;
  first.state = OdometryState::kTracking;
  first.recovered = recovering_;
  first.keyframe = true;
  first.keyframe_id = keyframe_id;
  first.keyframe_frame = first.index;
  first.tracking_ms = waiting_.front().ms;
  first.mapping_ms = keyframe_ms;
  poses.push_back(first);
  remember(first);
  const std::size_t n = waiting_.size();
  for (std::size_t j = 1; j < n; ++j) {
    const auto frame_start = std::chrono::steady_clock::now();
    const Eigen::Isometry3d guess = se3Exp(static_cast<double>(j) / static_cast<double>(n - 1) * se3Log(T_last_first));
    const OdometryFrame& frame_j = *waiting_[j].frame;
    const TrackingResult result = tracker_.track(*frame_j.pyramid, frame_j.fieldOrNull(), {guess}, 1.0, odometry_detail::edgeLayersOf(frame_j));
    FramePose pose;
    pose.index = frame_j.index;
    pose.time = frame_j.time;
    pose.T_world_cam = orthonormalized(T_world_first * result.T_cam_kf.inverse());
    pose.trusted = result.ok;
    pose.state = result.ok ? OdometryState::kTracking : OdometryState::kLost;
    pose.keyframe_id = keyframe_id;
    pose.keyframe_frame = first.index;
    pose.tracking = result;
    pose.tracking_ms = waiting_[j].ms + elapsedMs(frame_start);
    if (result.ok) {
      // In line in both modes: each waiting frame is tracked against the depths the ones before refined.
      MappingRequest request;
      request.frame = waiting_[j].frame;
      request.keyframe_id = keyframe_id;
      request.tracking = result;
      request.waited_for_initialization = true;
      const MappingOutcome outcome = mapNow(std::move(request));
      pose.mapping_ms = outcome.mapping_ms;
      trackAgainst(outcome.active);
      // The road set the map's scale: the waiting frames' poses, none out yet, go to metres with it
      // (about the map's first keyframe, which stays where it is).
      if (outcome.map_rescale != 1.0) {
        for (FramePose& before : poses) {
          scaleAbout(outcome.map_rescale, outcome.rescaled_about, &before.T_world_cam);
          before.tracking.scaleTranslation(outcome.map_rescale);
        }
        pose.T_world_cam = outcome.T_world_cam;
        pose.tracking.scaleTranslation(outcome.map_rescale);
        T_last_first.translation() *= outcome.map_rescale;  // the next frames' guesses
      }
    }
    poses.push_back(pose);
    remember(pose);
  }
  waiting_.clear();
  releaseFreedMemory();  // the burst: the frames that waited
  state_ = OdometryState::kTracking;
  recovering_ = relocalizing_ = false;
  return poses;
}

}  // namespace semantic_edge_vo
