// Odometry: the frame loop (track, check, recover, hand over to mapping) and its state;
// initialisation is in odometry_initialization.cpp, mapping in mapper.cpp.
#include "semantic_edge_vo/backend/odometry.h"

#include <utility>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "odometry_detail.h"
#include "semantic_edge_vo/backend/mapping_thread.h"
#include "semantic_edge_vo/common/robust_statistics.h"

namespace semantic_edge_vo {

using odometry_detail::elapsedMs;
using odometry_detail::edgeLayersOf;
using odometry_detail::gray8;

cv::Mat odometry_detail::gray8(const OdometryFrame& frame) {
  cv::Mat gray;
  frame.pyramid->level(0).intensity.convertTo(gray, CV_8U);
  return gray;
}

const char* toString(OdometryState state) {
  switch (state) {
    case OdometryState::kInitializing: return "initializing";
    case OdometryState::kTracking: return "tracking";
    case OdometryState::kLost: return "lost";
    case OdometryState::kUntrusted: return "untrusted";
  }
  return "unknown";
}

const char* toString(ScaleState state) {
  switch (state) {
    case ScaleState::kArbitrary: return "arbitrary";
    case ScaleState::kMeasured: return "measured";
    case ScaleState::kHeld: return "held";
  }
  return "unknown";
}

std::string OdometryOptions::validate() const {
  std::string error = tracker.validate();
  if (error.empty()) error = initializer.validate();
  if (error.empty()) error = epipolar.validate();
  if (error.empty()) error = window_optimizer.validate();
  if (error.empty()) error = keyframe_motion.validate();
  if (error.empty()) error = class_reliability.validate();
  if (error.empty()) error = consistency.validate();
  if (error.empty()) error = road.validate();
  if (error.empty() && !(keyframe_flow > 0 && keyframe_min_in_view >= 0 && keyframe_min_in_view <= 1))
    error = "keyframe_flow must be > 0 px and keyframe_min_in_view in [0, 1]";
  if (error.empty() && (keyframe_max_interval < 1 || window_size < 1 || !(depth_neighbour_radius > 0)))
    error = "keyframe_max_interval and window_size must be >= 1, depth_neighbour_radius > 0 px";
  if (error.empty() && mapping_queue < 1) error = "mapping_queue must be >= 1 frame";
  if (error.empty() && !(keyframe_min_parallax >= 0)) error = "keyframe_min_parallax must be >= 0 px";
  if (error.empty() && !(keyframe_min_inliers >= 0 && keyframe_min_inliers <= 1)) error = "keyframe_min_inliers must be in [0, 1]";
  return error;
}

const char* toString(MappingMode mode) { return mode == MappingMode::kParallel ? "parallel" : "deterministic"; }

bool parseMappingMode(const std::string& text, MappingMode* mode) {
  if (text != "deterministic" && text != "parallel") return false;
  *mode = text == "parallel" ? MappingMode::kParallel : MappingMode::kDeterministic;
  return true;
}

LiveTuning LiveTuning::of(const OdometryOptions& options) {
  LiveTuning tuning;
  tuning.photometric_huber = options.tracker.photometric_huber;
  tuning.edge_huber = options.tracker.edge_huber;
  tuning.keyframe_flow = options.keyframe_flow;
  tuning.keyframe_min_parallax = options.keyframe_min_parallax;
  tuning.keyframe_max_interval = options.keyframe_max_interval;
  return tuning;
}

void LiveTuning::applyTo(OdometryOptions* options) const {
  options->tracker.photometric_huber = photometric_huber;
  options->tracker.edge_huber = edge_huber;
  options->keyframe_flow = keyframe_flow;
  options->keyframe_min_parallax = keyframe_min_parallax;
  options->keyframe_max_interval = keyframe_max_interval;
}

void Odometry::tune(const LiveTuning& tuning) {
  tuning.applyTo(&options_);
  tracker_.setOptions(options_.tracker);
  pending_tuning_ = tuning;  // mapping takes it with the next request, in order
}

Odometry::Odometry(const OdometryOptions& options, const PinholeCamera& camera, MappingMode mode, std::shared_ptr<MappingLink> mapping)
    : options_(options),
      camera_(camera),
      tracker_(options.tracker),
      initializer_(options.initializer, camera),
      mapping_(mapping ? std::move(mapping) : std::make_shared<MappingThread>(options, camera)),
      parallel_(mode == MappingMode::kParallel) {}

std::vector<FramePose> Odometry::process(const std::shared_ptr<const OdometryFrame>& frame) {
  std::vector<FramePose> poses = processFrame(frame);
  for (FramePose& pose : poses) {
    pose.scale = scale_;
    pose.scale_confidence = scale_confidence_;
  }
  return poses;
}

void Odometry::noteScale(const MappingOutcome& outcome) {
  if (!options_.road.enabled()) return;
  if (outcome.map_rescale != 1.0) {  // the map's first road (under a keyframe, or any frame before one)
    map_scale_measured_ = true;
    scale_ = ScaleState::kMeasured;
  }
  if (!outcome.keyframe || !map_scale_measured_) return;  // arbitrary until the map's first road
  scale_confidence_ = outcome.window_keyframes > 0 ? static_cast<double>(outcome.road_keyframes) / outcome.window_keyframes : 0.0;
  scale_ = outcome.road_keyframes > 0 ? ScaleState::kMeasured : ScaleState::kHeld;
}

std::vector<FramePose> Odometry::processFrame(const std::shared_ptr<const OdometryFrame>& frame) {
  if (state_ != OdometryState::kTracking) {
    const auto start = std::chrono::steady_clock::now();
    std::vector<FramePose> poses;
    if (relocalizing_ && relocalize(frame, &poses)) return poses;
    return initialize(frame, start);
  }
  // The frame before asked for a keyframe: the next ones would be tracked farther and farther from
  // the old one (in a turn, hundreds of px). Tracking waits for it as it waits in deterministic
  // mode, but only until its points are triangulated (the provisional keyframe), not for the window.
  const auto start = std::chrono::steady_clock::now();
  if (parallel_ && keyframe_asked_) {
    keyframe_asked_->tracking_waits->store(true);
    mapping_->waitForFrame(keyframe_asked_->frame_index);
  }
  keyframe_asked_.reset();
  collectMapping();
  const double waited_ms = elapsedMs(start);
  FramePose pose = track(frame);
  pose.tracking_ms += waited_ms;
  return {pose};
}

void Odometry::collectMapping() {
  if (!parallel_) return;
  // The newest pose was tracked against keyframe_, where tracking had it; it moves as the window
  // has moved that keyframe since, or, when the frame itself became a keyframe, as the window moved it.
  int anchor_id = keyframe_ ? keyframe_->id : -1;
  Eigen::Isometry3d anchor_pose = keyframe_ ? keyframe_->T_world_cam : Eigen::Isometry3d::Identity();
  const MappingOutcome* newest = nullptr;
  double rescale = 1.0;  // the map's scale was set meanwhile
  std::string error;
  const std::vector<MappingOutcome> outcomes = mapping_->takeOutcomes();
  for (const MappingOutcome& outcome : outcomes) {
    mapping_dropped_ += outcome.dropped && outcome.error.empty();
    if (!outcome.error.empty()) error = outcome.error;
    if (outcome.stale || outcome.dropped) continue;
    newest = &outcome;
    noteScale(outcome);
    rescale *= outcome.map_rescale;
    if (outcome.keyframe) new_windows_.push_back(outcome.window);
    if (outcome.provisional && outcome.frame_index == motion_.lastStamp().index) {
      anchor_id = outcome.active->id;
      anchor_pose = motion_.lastPose();
    }
  }
  if (newest) {
    // Odom jumps once by this correction (docs/architecture.md); the velocity is kept.
    const auto moved = newest->keyframe_poses.find(anchor_id);
    if (moved != newest->keyframe_poses.end()) {
      motion_.correct(moved->second * anchor_pose.inverse());
      // The recent frames' motion from the keyframe they were tracked against, at the map's new scale.
      if (rescale != 1.0) motion_.rescale(rescale, moved->second.translation());
    }
    trackAgainst(newest->active);
  }
  if (!error.empty()) throw std::runtime_error("mapping dropped a frame it failed on: " + error);
}

void Odometry::finishMapping() {
  mapping_->waitUntilIdle();
  collectMapping();
}

MappingOutcome Odometry::mapNow(MappingRequest request) {
  const int frame_index = request.frame->index;
  request.tuning = std::exchange(pending_tuning_, std::nullopt);
  mapping_->post(std::move(request));
  mapping_->waitUntilIdle();
  for (MappingOutcome& outcome : mapping_->takeOutcomes())
    if (outcome.frame_index == frame_index && !outcome.provisional) {
      if (!outcome.error.empty()) throw std::runtime_error("mapping failed on frame " + std::to_string(frame_index) + ": " + outcome.error);
      if (outcome.dropped) throw std::runtime_error("mapping dropped frame " + std::to_string(frame_index));
      noteScale(outcome);
      if (outcome.map_rescale != 1.0) motion_.rescale(outcome.map_rescale, outcome.rescaled_about);  // the last frame's pose, at the old scale
      return outcome;
    }
  throw std::runtime_error("mapping gave no outcome for frame " + std::to_string(frame_index));
}

std::vector<std::shared_ptr<const KeyframeWindow>> Odometry::takeNewWindows() {
  std::vector<std::shared_ptr<const KeyframeWindow>> windows;
  windows.swap(new_windows_);
  return windows;
}

void Odometry::trackAgainst(std::shared_ptr<const Keyframe> keyframe) {
  keyframe_ = std::move(keyframe);
  tracker_.setKeyframe(keyframe_);
}

void Odometry::restart() {
  relocalizing_ = false;  // a new map was asked for
  keyframe_asked_.reset();
  if (state_ != OdometryState::kTracking) return;
  state_ = OdometryState::kInitializing;
  recovering_ = true;
  untrusted_in_a_row_ = 0;
  // The speed it drove at over the last second, not the last frame's (traffic that made the loss may
  // have dragged it towards standing) nor that of the last minutes (a car slows into a turn).
  const double driving_speed = motion_.drivingMotion(kRestartMotions).head<3>().norm();
  speed_at_restart_ = driving_speed > 0.0 ? driving_speed : motion_.frameMotion().translation().norm();
}

std::vector<FramePose> Odometry::flush() {
  std::vector<FramePose> poses;
  for (const WaitingFrame& waiting : waiting_) {
    FramePose pose;
    pose.index = waiting.frame->index;
    pose.time = waiting.frame->time;
    pose.T_world_cam = motion_.predict(stampOf(*waiting.frame));
    pose.state = OdometryState::kInitializing;
    pose.tracking_ms = waiting.ms;
    poses.push_back(pose);
  }
  waiting_.clear();
  return poses;
}

std::vector<Eigen::Isometry3d> Odometry::guesses(const Keyframe& keyframe, const OdometryFrame& frame) const {
  std::vector<Eigen::Isometry3d> guesses;
  for (const Eigen::Isometry3d& T_world_cam : motion_.guesses(stampOf(frame))) guesses.push_back(T_world_cam.inverse() * keyframe.T_world_cam);
  return guesses;
}

bool Odometry::relocalize(const std::shared_ptr<const OdometryFrame>& frame, std::vector<FramePose>* poses) {
  const auto start = std::chrono::steady_clock::now();
  const TrackingResult result =
      tracker_.track(*frame->pyramid, frame->fieldOrNull(), guesses(*keyframe_, *frame), last_inlier_ratio_, edgeLayersOf(*frame));
  // Only a map that explains the frame about as well as it did the frames before the loss: a loss
  // of the view (an occlusion, a flash) finds it again; a map gone wrong (traffic close by made the
  // loss, and it explains the next frame just above min_inlier_ratio) is initialised anew.
  if (!result.ok || recent_inlier_ratios_.empty()) return false;
  const double usual_ratio = median({recent_inlier_ratios_.begin(), recent_inlier_ratios_.end()});
  if (result.inlierRatio() < options_.tracker.accept_inlier_ratio * usual_ratio) return false;
  // Back on the map it had: the frames since the loss stay untrusted predictions.
  *poses = flush();
  for (const FramePose& pose : *poses) remember(pose);
  state_ = OdometryState::kTracking;
  recovering_ = relocalizing_ = false;
  FramePose pose = trackedPose(frame, result, true, elapsedMs(start));
  pose.recovered = true;
  poses->push_back(pose);
  return true;
}

FramePose Odometry::track(const std::shared_ptr<const OdometryFrame>& frame) {
  const auto start = std::chrono::steady_clock::now();
  const std::vector<Eigen::Isometry3d> initial = guesses(*keyframe_, *frame);
  TrackingResult result = tracker_.track(*frame->pyramid, frame->fieldOrNull(), initial, last_inlier_ratio_, edgeLayersOf(*frame));
  double motion_deviation = 0.0;
  const bool consistent = !result.ok || retrackUnlessConsistent(*frame, initial.front(), &result, &motion_deviation);
  FramePose pose = trackedPose(frame, result, consistent, elapsedMs(start));
  pose.motion_deviation = motion_deviation;
  return pose;
}

FrameAgreement Odometry::agreementOf(const OdometryFrame& frame, const TrackingResult& result) const {
  const Eigen::Isometry3d T_last_world = motion_.lastPose().inverse();
  const Eigen::Vector3d travel = (T_last_world * keyframe_->T_world_cam * result.T_cam_kf.inverse()).translation();
  const Eigen::Vector3d predicted = (T_last_world * motion_.predictAtTrackedVelocity(stampOf(frame))).translation();
  const double usual_travel = motion_.drivingMotion().head<3>().norm() * motion_.framesBetween(motion_.lastStamp(), stampOf(frame));
  const double usual_ratio = median({recent_inlier_ratios_.begin(), recent_inlier_ratios_.end()});
  return compareWithRecentFrames(result.inlierRatio(), usual_ratio, options_.tracker.accept_inlier_ratio, travel, predicted,
                                 usual_travel, options_.consistency);
}

bool Odometry::retrackUnlessConsistent(const OdometryFrame& frame, const Eigen::Isometry3d& prediction, TrackingResult* result,
                                       double* motion_deviation) {
  const FrameAgreement agreement = agreementOf(frame, *result);
  *motion_deviation = agreement.motion_deviation;
  if (agreement.ok()) return true;
  std::vector<TrackingResult> alternatives = {tracker_.track(*frame.pyramid, nullptr, {prediction})};
  if (frame.has_field && tracker_.hasAllEdgesLayer())
    alternatives.push_back(tracker_.track(*frame.pyramid, &frame.field, {prediction}, 1.0, EdgeLayers::kAllEdges));
  // Of the solutions whose motion agrees with the recent frames (this one may, with fewer inliers
  // than they had: a turn brings new content), the one with the most inliers is taken. None: the
  // frame is not trusted.
  TrackingResult best = *result;
  bool found = agreement.motion_ok;
  int iterations = result->iterations;
  for (const TrackingResult& alternative : alternatives) {
    iterations += alternative.iterations;
    if (alternative.ok && agreementOf(frame, alternative).motion_ok && (!found || alternative.inlierRatio() > best.inlierRatio())) {
      best = alternative;
      found = true;
    }
  }
  *result = best;
  result->iterations = iterations;
  if (found) *motion_deviation = agreementOf(frame, *result).motion_deviation;
  return found;
}

FramePose Odometry::trackedPose(const std::shared_ptr<const OdometryFrame>& frame, const TrackingResult& result, bool consistent,
                                double tracking_ms) {
  FramePose pose;
  pose.index = frame->index;
  pose.time = frame->time;
  pose.keyframe_id = keyframe_->id;
  pose.keyframe_frame = keyframe_->frame ? keyframe_->frame->index : -1;
  pose.tracking = result;
  pose.tracking_ms = tracking_ms;
  if (result.ok && !consistent) return untrustedPose(*frame, pose);
  untrusted_in_a_row_ = 0;
  last_inlier_ratio_ = pose.tracking.ok ? pose.tracking.inlierRatio() : 1.0;
  if (!pose.tracking.ok) {
    // Lost: report the prediction, untrusted; from the next frame on, try the map it had until a
    // new initialisation succeeds.
    pose.T_world_cam = motion_.predict(stampOf(*frame));
    pose.state = OdometryState::kLost;
    restart();
    relocalizing_ = true;
    remember(pose);
    return pose;
  }
  pose.T_world_cam = orthonormalized(keyframe_->T_world_cam * pose.tracking.T_cam_kf.inverse());
  pose.trusted = true;
  pose.state = OdometryState::kTracking;
  MappingRequest request;
  request.frame = frame;
  request.keyframe_id = keyframe_->id;
  request.tracking = pose.tracking;
  if (parallel_) {
    if (pose.tracking.mean_flow > options_.keyframe_flow) {
      request.tracking_waits = std::make_shared<std::atomic<bool>>(false);
      keyframe_asked_ = KeyframeAsked{frame->index, request.tracking_waits};
    }
    request.tuning = std::exchange(pending_tuning_, std::nullopt);
    mapping_->post(std::move(request));
    remember(pose);
    return pose;
  }
  const MappingOutcome outcome = mapNow(std::move(request));
  pose.mapping_ms = outcome.mapping_ms;
  pose.window_ms = outcome.window_ms;
  pose.keyframe_scale = outcome.keyframe_scale;
  trackAgainst(outcome.active);
  // A keyframe refused for its scale: the frame's pose is not to be trusted either.
  if (outcome.refused) return untrustedPose(*frame, pose);
  if (outcome.keyframe) {
    pose.keyframe = true;
    pose.window_correction = outcome.window_correction;
    new_windows_.push_back(outcome.window);
  }
  if (outcome.keyframe || outcome.map_rescale != 1.0) pose.T_world_cam = outcome.T_world_cam;  // moved by the window or rescaled
  if (outcome.map_rescale != 1.0) pose.tracking.scaleTranslation(outcome.map_rescale);
  remember(pose);
  return pose;
}

FramePose Odometry::untrustedPose(const OdometryFrame& frame, FramePose pose) {
  pose.T_world_cam = motion_.predict(stampOf(frame));
  pose.trusted = false;
  pose.state = OdometryState::kUntrusted;
  if (++untrusted_in_a_row_ > options_.consistency.max_untrusted_frames) {
    pose.state = OdometryState::kLost;
    restart();
    relocalizing_ = true;
  }
  remember(pose);
  return pose;
}

void Odometry::remember(const FramePose& pose) {
  motion_.remember(pose.T_world_cam, {pose.index, pose.time}, pose.trusted, pose.window_correction);
  if (pose.trusted && pose.tracking.ok) keepLast(pose.tracking.inlierRatio(), kRecentInlierRatios, &recent_inlier_ratios_);
}

}  // namespace semantic_edge_vo
