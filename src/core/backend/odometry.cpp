#include "semantic_edge_vo/common/robust_statistics.h"
#include "semantic_edge_vo/backend/odometry.h"
#include "semantic_edge_vo/common/parallel_slices.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>

namespace semantic_edge_vo {
namespace {

double elapsedMs(std::chrono::steady_clock::time_point since) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - since).count();
}

std::shared_ptr<const SharedClassEdgeTest> edgeTestOf(const OdometryFrame& frame, double radius) {
  return frame.has_field ? std::make_shared<const SharedClassEdgeTest>(frame.field, radius) : nullptr;
}

/// Appends the value, keeping the newest `count` values.
template <typename T>
void keepLast(const T& value, std::size_t count, std::deque<T>* values) {
  values->push_back(value);
  if (values->size() > count) values->pop_front();
}

cv::Mat gray8(const OdometryFrame& frame) {
  cv::Mat gray;
  frame.pyramid->level(0).intensity.convertTo(gray, CV_8U);
  return gray;
}

/// A measured inverse depth at a pixel of the keyframe that receives it.
struct DepthSample {
  Eigen::Vector2d pixel;
  double inverse_depth;
};

/// Points without a measurement take the median of the samples within `radius` (bucketed), or of
/// all samples, as a prior with a wide variance; the epipolar search then measures them.
void propagateDepths(const std::vector<DepthSample>& samples, const PinholeCamera& camera, double radius,
                     double default_inverse_depth, std::vector<MapPoint>* points) {
  const int cols = static_cast<int>(std::ceil(camera.width / radius)), rows = static_cast<int>(std::ceil(camera.height / radius));
  std::vector<std::vector<const DepthSample*>> buckets(static_cast<std::size_t>(cols * rows));
  std::vector<double> all;
  for (const DepthSample& sample : samples) {
    const int bx = std::clamp(static_cast<int>(sample.pixel.x() / radius), 0, cols - 1);
    const int by = std::clamp(static_cast<int>(sample.pixel.y() / radius), 0, rows - 1);
    buckets[static_cast<std::size_t>(by * cols + bx)].push_back(&sample);
    all.push_back(sample.inverse_depth);
  }
  const double fallback = all.empty() ? default_inverse_depth : median(all);
  std::vector<double> near;
  for (MapPoint& point : *points) {
    if (point.hasDepth()) continue;
    near.clear();
    const int bx = static_cast<int>(point.u / radius), by = static_cast<int>(point.v / radius);
    for (int y = std::max(0, by - 1); y <= std::min(rows - 1, by + 1); ++y)
      for (int x = std::max(0, bx - 1); x <= std::min(cols - 1, bx + 1); ++x)
        for (const DepthSample* sample : buckets[static_cast<std::size_t>(y * cols + x)])
          if ((sample->pixel - Eigen::Vector2d(point.u, point.v)).norm() <= radius) near.push_back(sample->inverse_depth);
    point.inverse_depth = near.empty() ? fallback : median(near);
    point.inverse_depth_variance = std::pow((near.empty() ? 1.0 : 0.5) * point.inverse_depth, 2);
    point.observations = 0;
  }
}

}  // namespace

const char* toString(OdometryState state) {
  switch (state) {
    case OdometryState::kInitializing: return "initializing";
    case OdometryState::kTracking: return "tracking";
    case OdometryState::kLost: return "lost";
    case OdometryState::kUntrusted: return "untrusted";
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
  if (error.empty() && !(keyframe_flow > 0 && keyframe_min_in_view >= 0 && keyframe_min_in_view <= 1))
    error = "keyframe_flow must be > 0 px and keyframe_min_in_view in [0, 1]";
  if (error.empty() && (keyframe_max_interval < 1 || window_size < 1 || !(depth_neighbour_radius > 0)))
    error = "keyframe_max_interval and window_size must be >= 1, depth_neighbour_radius > 0 px";
  if (error.empty() && window_delay < 0) error = "window_delay must be >= 0 frames";
  if (error.empty() && !(keyframe_min_parallax >= 0)) error = "keyframe_min_parallax must be >= 0 px";
  return error;
}

Odometry::Odometry(const OdometryOptions& options, const PinholeCamera& camera)
    : options_(options),
      camera_(camera),
      tracker_(options.tracker),
      window_optimizer_(options.window_optimizer),
      deferred_window_(window_optimizer_),
      initializer_(options.initializer, camera),
      keyframe_motion_(options.keyframe_motion, camera),
      class_reliability_(options.class_reliability) {}

std::vector<FramePose> Odometry::process(const std::shared_ptr<const OdometryFrame>& frame) {
  if (state_ != OdometryState::kTracking) {
    const auto start = std::chrono::steady_clock::now();
    std::vector<FramePose> poses;
    if (relocalizing_ && relocalize(frame, &poses)) return poses;
    return initialize(frame, start);
  }
  FramePose merged;
  if (deferred_window_.running() && frame->index >= merge_window_at_) {
    mergeWindow(&merged);
    tracker_.setKeyframe(active_);  // its pose and depths may have moved
  }
  FramePose pose = track(frame);
  pose.window_ms += merged.window_ms;
  pose.mapping_ms += merged.mapping_ms;
  return {pose};
}

void Odometry::restart() {
  relocalizing_ = false;  // a new map was asked for
  if (state_ != OdometryState::kTracking) return;
  state_ = OdometryState::kInitializing;
  recovering_ = true;
  untrusted_in_a_row_ = 0;
  // The speed it drove at over the last second, not the last frame's (traffic that made the loss may
  // have dragged it towards standing) nor that of the last minutes (a car slows into a turn).
  const double driving_speed = drivingMotion(kRestartMotions).head<3>().norm();
  speed_at_restart_ = driving_speed > 0.0 ? driving_speed : frameMotion().translation().norm();
}

std::vector<FramePose> Odometry::flush() {
  std::vector<FramePose> poses;
  for (const WaitingFrame& waiting : waiting_) {
    FramePose pose;
    pose.index = waiting.frame->index;
    pose.time = waiting.frame->time;
    pose.T_world_cam = predict(*waiting.frame);
    pose.state = OdometryState::kInitializing;
    pose.tracking_ms = waiting.ms;
    poses.push_back(pose);
  }
  waiting_.clear();
  return poses;
}

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

  // The first waiting frame becomes the first keyframe, anchored where the odometry predicts it
  // (identity at the very start), so that odom stays continuous after a loss.
  Eigen::Isometry3d T_last_first = initializer_.T_last_first();
  double depth_scale = 1.0;
  bool scale_carried = false;
  if (recovering_ && poses_seen_ >= 2) {
    const double speed = speed_at_restart_;  // per frame interval
    const double baseline = T_last_first.translation().norm();
    scale_carried = speed > 0.0 && baseline > 0.0;
    if (scale_carried) depth_scale = speed * framesBetween(stampOf(*waiting_.front().frame), stampOf(*waiting_.back().frame)) / baseline;
  }
  if (!scale_carried) driving_motions_.clear();  // travel at another map's scale
  T_last_first.translation() *= depth_scale;
  const Eigen::Isometry3d T_world_first = predict(*waiting_.front().frame);

  auto keyframe = std::make_shared<Keyframe>();
  keyframe->id = next_keyframe_id_++;
  keyframe->T_world_cam = T_world_first;
  keyframe->frame = waiting_.front().frame;
  takeCandidates(keyframe.get());
  const std::vector<double>& inverse_depths = initializer_.inverseDepths();
  for (std::size_t i = 0; i < keyframe->points.size(); ++i) {
    if (!(inverse_depths[i] > 0.0)) continue;
    MapPoint& point = keyframe->points[i];
    point.inverse_depth = inverse_depths[i] / depth_scale;
    point.inverse_depth_variance = std::pow(0.1 * point.inverse_depth, 2);
    point.observations = 1;
  }
  std::vector<DepthSample> samples;
  for (const MapPoint& point : keyframe->points)
    if (point.hasDepth()) samples.push_back({Eigen::Vector2d(point.u, point.v), point.inverse_depth});
  propagateDepths(samples, camera_, options_.depth_neighbour_radius, 1.0 / options_.initializer.median_depth, &keyframe->points);
  keyframes_.push_back(keyframe);
  setActiveKeyframe(keyframe);

  std::vector<FramePose> poses;
  FramePose first;
  first.index = keyframe->frame->index;
  first.time = keyframe->frame->time;
  first.T_world_cam = T_world_first;
  first.trusted = true;
  first.state = OdometryState::kTracking;
  first.recovered = recovering_;
  first.keyframe = true;
  first.keyframe_id = keyframe->id;
  first.tracking_ms = waiting_.front().ms;
  first.mapping_ms = elapsedMs(keyframe_start);
  poses.push_back(first);
  remember(first);
  const std::size_t n = waiting_.size();
  for (std::size_t j = 1; j < n; ++j) {
    const auto frame_start = std::chrono::steady_clock::now();
    const Eigen::Isometry3d guess = se3Exp(static_cast<double>(j) / static_cast<double>(n - 1) * se3Log(T_last_first));
    const OdometryFrame& frame_j = *waiting_[j].frame;
    const TrackingResult result = tracker_.track(*frame_j.pyramid, frame_j.fieldOrNull(), {guess});
    FramePose pose;
    pose.index = frame_j.index;
    pose.time = frame_j.time;
    pose.T_world_cam = orthonormalized(T_world_first * result.T_cam_kf.inverse());
    pose.trusted = result.ok;
    pose.state = result.ok ? OdometryState::kTracking : OdometryState::kLost;
    pose.keyframe_id = keyframe->id;
    pose.tracking = result;
    pose.tracking_ms = waiting_[j].ms + elapsedMs(frame_start);
    const auto mapping_start = std::chrono::steady_clock::now();
    if (result.ok) {
      refineDepths(frame_j, result.T_cam_kf);
      followCorners(frame_j);
    }
    pose.mapping_ms = elapsedMs(mapping_start);
    poses.push_back(pose);
    remember(pose);
  }
  waiting_.clear();
  state_ = OdometryState::kTracking;
  recovering_ = relocalizing_ = false;
  frames_since_keyframe_ = static_cast<int>(n) - 1;
  return poses;
}

std::vector<Eigen::Isometry3d> Odometry::guesses(const Keyframe& keyframe, const OdometryFrame& frame) const {
  std::vector<Eigen::Isometry3d> world_poses = {T_world_last_};
  if (poses_seen_ >= 2) {
    const Vector6d velocity = se3Log(frameMotion());
    const double n = framesToExtrapolate(frame);
    // Constant velocity first, then no motion, half and double the velocity.
    world_poses = {T_world_last_ * se3Exp(n * velocity), T_world_last_, T_world_last_ * se3Exp(0.5 * n * velocity),
                   T_world_last_ * se3Exp(2.0 * n * velocity)};
    // Standing, or nearly: the guesses above all say "no motion". A car drives off the way it came:
    // one frame's travel at the speed it drove at before is one more (a start that the frames caught
    // late, or dropped; not times the frames missed: a car starting from rest covers less).
    const Vector6d driving = drivingMotion();
    if (velocity.head<3>().norm() < kStandingFraction * driving.head<3>().norm()) world_poses.push_back(T_world_last_ * se3Exp(driving));
  }
  std::vector<Eigen::Isometry3d> guesses;
  for (const Eigen::Isometry3d& T_world_cam : world_poses) guesses.push_back(T_world_cam.inverse() * keyframe.T_world_cam);
  return guesses;
}

bool Odometry::relocalize(const std::shared_ptr<const OdometryFrame>& frame, std::vector<FramePose>* poses) {
  const auto start = std::chrono::steady_clock::now();
  const TrackingResult result = tracker_.track(*frame->pyramid, frame->fieldOrNull(), guesses(*active_, *frame), last_inlier_ratio_);
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
  const std::vector<Eigen::Isometry3d> initial = guesses(*active_, *frame);
  TrackingResult result = tracker_.track(*frame->pyramid, frame->fieldOrNull(), initial, last_inlier_ratio_);
  double motion_deviation = 0.0;
  const bool consistent = !result.ok || retrackUnlessConsistent(*frame, initial.front(), &result, &motion_deviation);
  FramePose pose = trackedPose(frame, result, consistent, elapsedMs(start));
  pose.motion_deviation = motion_deviation;
  return pose;
}

FrameAgreement Odometry::agreementOf(const OdometryFrame& frame, const TrackingResult& result) const {
  const Eigen::Isometry3d T_last_world = T_world_last_.inverse();
  const Eigen::Vector3d travel = (T_last_world * active_->T_world_cam * result.T_cam_kf.inverse()).translation();
  const Eigen::Vector3d predicted = (T_last_world * predict(frame)).translation();
  const double usual_travel = drivingMotion().head<3>().norm() * framesBetween(last_stamp_, stampOf(frame));
  const double usual_ratio = recent_inlier_ratios_.empty() ? 0.0 : median({recent_inlier_ratios_.begin(), recent_inlier_ratios_.end()});
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
  pose.keyframe_id = active_->id;
  pose.tracking = result;
  pose.tracking_ms = tracking_ms;
  if (result.ok && !consistent) return untrustedPose(*frame, pose);
  untrusted_in_a_row_ = 0;
  last_inlier_ratio_ = pose.tracking.ok ? pose.tracking.inlierRatio() : 1.0;
  if (!pose.tracking.ok) {
    // Lost: report the prediction, untrusted; from the next frame on, try the map it had until a
    // new initialisation succeeds.
    pose.T_world_cam = predict(*frame);
    pose.state = OdometryState::kLost;
    restart();
    relocalizing_ = true;
    remember(pose);
    return pose;
  }
  pose.T_world_cam = orthonormalized(active_->T_world_cam * pose.tracking.T_cam_kf.inverse());
  pose.trusted = true;
  pose.state = OdometryState::kTracking;
  const auto mapping_start = std::chrono::steady_clock::now();
  std::shared_ptr<const SharedClassEdgeTest> frame_edges = refineDepths(*frame, pose.tracking.T_cam_kf);
  followCorners(*frame);
  if (frame->has_field) class_reliability_.observe(*active_, pose.tracking.T_cam_kf, frame->field);
  ++frames_since_keyframe_;
  const bool few_in_view = pose.tracking.points_in_view < options_.keyframe_min_in_view * pose.tracking.points;
  // The interval only while the camera travels: standing, a keyframe would measure no depth.
  const bool interval = frames_since_keyframe_ >= options_.keyframe_max_interval &&
                        travelParallax(*active_, pose.tracking.T_cam_kf) >= options_.keyframe_min_parallax;
  if (pose.tracking.mean_flow > options_.keyframe_flow || few_in_view || interval) {
    if (!makeKeyframe(frame, std::move(frame_edges), &pose)) {
      pose.mapping_ms = elapsedMs(mapping_start);
      return untrustedPose(*frame, pose);
    }
    pose.keyframe = true;
  }
  pose.mapping_ms = elapsedMs(mapping_start);
  remember(pose);
  return pose;
}

FramePose Odometry::untrustedPose(const OdometryFrame& frame, FramePose pose) {
  pose.T_world_cam = predict(frame);
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

double Odometry::travelParallax(const Keyframe& keyframe, const Eigen::Isometry3d& T_frame_kf) const {
  std::vector<double> flows;
  for (const MapPoint& point : keyframe.points) {
    if (!point.hasDepth()) continue;
    const Eigen::Vector3d p = camera_.backProject(point.u, point.v, 1.0 / point.inverse_depth);
    const Eigen::Vector3d rotated = T_frame_kf.linear() * p, moved = rotated + T_frame_kf.translation();
    if (rotated.z() <= 1e-3 || moved.z() <= 1e-3) continue;
    flows.push_back((camera_.project(moved) - camera_.project(rotated)).norm());
  }
  return median(flows);
}

std::shared_ptr<const SharedClassEdgeTest> Odometry::refineDepths(const OdometryFrame& frame, const Eigen::Isometry3d& T_frame_kf) {
  const PyramidLevel& host = active_->frame->pyramid->level(0);
  const PyramidLevel& target = frame.pyramid->level(0);
  std::shared_ptr<const SharedClassEdgeTest> edges = edgeTestOf(frame, options_.epipolar.edge_radius);
  measureDepths(host, {&target, edges.get(), T_frame_kf}, &active_->points);
  tracker_.setKeyframe(active_);
  return edges;
}

bool Odometry::makeKeyframe(const std::shared_ptr<const OdometryFrame>& frame, std::shared_ptr<const SharedClassEdgeTest> frame_edges,
                            FramePose* pose) {
  // One deferred optimisation at a time: the previous one is merged first, and the new keyframe,
  // tracked against the active one, moves with it.
  if (deferred_window_.running()) pose->T_world_cam = mergeWindow(pose) * pose->T_world_cam;
  auto keyframe = std::make_shared<Keyframe>();
  keyframe->T_world_cam = pose->T_world_cam;
  keyframe->frame = frame;
  // Its points triangulated from the tracked pose must see the map at the map's scale: a keyframe
  // whose depths disagree with it by more than the bound would hand the next frames a new scale.
  pose->keyframe_scale = triangulatePoints(keyframe.get(), *active_);
  if (std::abs(std::log(pose->keyframe_scale)) > std::log1p(options_.consistency.max_keyframe_scale_change)) return false;
  std::vector<MapPoint> from_tracked_pose = std::move(keyframe->points);
  keyframe->points.clear();
  keyframe->id = next_keyframe_id_++;
  keyframe->edge_test = std::move(frame_edges);
  keyframe->measured_motion = keyframe_motion_.measure(frame->index, (active_->T_world_cam.inverse() * keyframe->T_world_cam).linear());
  reanchor(keyframe->measured_motion, options_.keyframe_motion, active_->T_world_cam, &keyframe->T_world_cam);
  keyframes_.push_back(keyframe);
  while (static_cast<int>(keyframes_.size()) > options_.window_size) keyframes_.pop_front();
  // The window settles the new pose against the older keyframes' points before the new points are
  // triangulated from it: points triangulated from the tracked pose agree with its error and would
  // pin it there (a yaw error leaves a left-right depth gradient that makes the next yaw error).
  if (options_.optimize_window) optimizeWindow(frame->index, pose);
  // Triangulated again unless nothing moved since (the window deferred or off, no re-anchoring).
  const bool settled_in_line = options_.optimize_window && options_.window_delay == 0;
  if (settled_in_line || !keyframe->T_world_cam.isApprox(pose->T_world_cam)) triangulatePoints(keyframe.get(), *active_);
  else keyframe->points = std::move(from_tracked_pose);
  setActiveKeyframe(keyframe);
  frames_since_keyframe_ = 0;
  pose->T_world_cam = keyframe->T_world_cam;
  return true;
}

double Odometry::triangulatePoints(Keyframe* keyframe, const Keyframe& previous) const {
  takeCandidates(keyframe);
  // Prior depths: the previous keyframe's measured points, seen from the new keyframe.
  const Eigen::Isometry3d T_new_old = keyframe->T_world_cam.inverse() * previous.T_world_cam;
  std::vector<DepthSample> samples;
  for (const MapPoint& point : previous.points) {
    if (!point.hasDepth()) continue;
    const Eigen::Vector3d p = T_new_old * camera_.backProject(point.u, point.v, 1.0 / point.inverse_depth);
    const Eigen::Vector2d pixel = camera_.project(p);
    if (p.z() > 1e-3 && camera_.contains(pixel.x(), pixel.y())) samples.push_back({pixel, 1.0 / p.z()});
  }
  propagateDepths(samples, camera_, options_.depth_neighbour_radius, 1.0 / options_.initializer.median_depth, &keyframe->points);
  std::vector<double> priors(keyframe->points.size(), 0.0);  // of the points with map points near
  for (std::size_t i = 0; i < priors.size(); ++i)
    if (keyframe->points[i].inverse_depth_variance < std::pow(0.75 * keyframe->points[i].inverse_depth, 2)) priors[i] = keyframe->points[i].inverse_depth;
  const PyramidLevel& host = keyframe->frame->pyramid->level(0);
  const std::shared_ptr<const SharedClassEdgeTest> previous_edges =
      previous.edge_test ? previous.edge_test : edgeTestOf(*previous.frame, options_.epipolar.edge_radius);
  measureDepths(host, {&previous.frame->pyramid->level(0), previous_edges.get(), T_new_old.inverse()}, &keyframe->points);
  std::vector<double> ratios;  // inverse depths measured over the map's
  for (std::size_t i = 0; i < priors.size(); ++i)
    if (priors[i] > 0.0 && keyframe->points[i].observations > 0) ratios.push_back(keyframe->points[i].inverse_depth / priors[i]);
  constexpr std::size_t kMinRatios = 20;  // fewer: no say on the scale
  return ratios.size() < kMinRatios ? 1.0 : 1.0 / median(ratios);
}

void Odometry::measureDepths(const PyramidLevel& host, const EpipolarTarget& target, std::vector<MapPoint>* points) const {
  // Each point is searched and filtered on its own: both cores, same result as in order.
  forEachIndex(points->size(), [&](std::size_t i) {
    DepthMeasurement measurement;
    MapPoint& point = (*points)[i];
    if (searchEpipolar(point, host, *target.level, target.edges, target.T_target_host, options_.epipolar, &measurement))
      fuseDepth(measurement, &point);
  });
}

void Odometry::optimizeWindow(int frame_index, FramePose* pose) {
  if (options_.window_delay > 0) {
    deferred_window_.start(keyframes_);
    merge_window_at_ = frame_index + options_.window_delay;
    return;
  }
  const auto start = std::chrono::steady_clock::now();
  window_optimizer_.optimize(keyframes_);
  pose->window_ms += elapsedMs(start);
}

Eigen::Isometry3d Odometry::mergeWindow(FramePose* pose) {
  const DeferredWindowOptimization::Merge merge = deferred_window_.finish(keyframes_);
  pose->window_ms += merge.optimization_ms;
  pose->mapping_ms += merge.waited_ms;
  const auto moved = merge.corrections.find(active_->id);
  if (moved == merge.corrections.end()) return Eigen::Isometry3d::Identity();
  const Eigen::Isometry3d& correction = moved->second;
  T_world_last_ = orthonormalized(correction * T_world_last_);
  T_world_before_ = orthonormalized(correction * T_world_before_);
  // The optimisation settled the active keyframe's pose without its points (see makeKeyframe), which
  // were triangulated from the tracked pose meanwhile: triangulate them again from the settled one.
  if (keyframes_.size() >= 2) triangulatePoints(active_.get(), *keyframes_[keyframes_.size() - 2]);
  return correction;
}

void Odometry::setActiveKeyframe(std::shared_ptr<Keyframe> keyframe) {
  active_ = std::move(keyframe);
  tracker_.setKeyframe(active_);
  if (keyframe_motion_.enabled()) keyframe_motion_.start(active_->id, active_->frame->index, gray8(*active_->frame));
}

void Odometry::takeCandidates(Keyframe* keyframe) const {
  keyframe->points = keyframe->frame->candidates;
  const int all_edges_layer = keyframe->frame->has_field ? keyframe->frame->field.all_edges_layer : -1;
  for (MapPoint& point : keyframe->points)
    if (point.isEdge()) point.field_layers = class_reliability_.fieldLayers(point.class_mask, all_edges_layer);
}

void Odometry::followCorners(const OdometryFrame& frame) {
  if (keyframe_motion_.enabled()) keyframe_motion_.follow(frame.index, gray8(frame));
}

void Odometry::remember(const FramePose& pose) {
  T_world_before_ = T_world_last_;
  T_world_last_ = orthonormalized(pose.T_world_cam);
  before_stamp_ = last_stamp_;
  last_stamp_ = {pose.index, pose.time};
  if (pose.trusted) last_trusted_stamp_ = last_stamp_;
  ++poses_seen_;
  const int indices = last_stamp_.index - before_stamp_.index;
  const double seconds = last_stamp_.time - before_stamp_.time;
  if (poses_seen_ >= 2 && indices > 0 && seconds > 0.0) keepLast(seconds / indices, kFrameIntervals, &frame_intervals_);
  if (pose.trusted && pose.tracking.ok) keepLast(pose.tracking.inlierRatio(), kRecentInlierRatios, &recent_inlier_ratios_);
  if (!pose.trusted || poses_seen_ < 2) return;
  // Only motions of a driving camera are kept: the store outlasts a stop of any length.
  Vector6d motion = se3Log(frameMotion());
  if (motion.head<3>().norm() < kStandingFraction * drivingMotion().head<3>().norm()) return;
  motion.tail<3>().setZero();  // the travel; a turn it made then says nothing of the start
  keepLast(motion, kDrivingMotions, &driving_motions_);
}

double Odometry::framesBetween(const FrameStamp& from, const FrameStamp& to) const {
  const double interval = median({frame_intervals_.begin(), frame_intervals_.end()});
  const double frames = interval > 0.0 ? (to.time - from.time) / interval : static_cast<double>(to.index - from.index);
  return frames >= 1.0 ? std::round(frames) : 1.0;  // also 1 for a stamp that is not a number
}

double Odometry::framesToExtrapolate(const OdometryFrame& frame) const {
  // Dead reckoning ends kMaxDeadReckoning frames after the last trusted pose: the car may have
  // stopped since (a loss it never finds its map again from would otherwise drive on for ever).
  const double since_trusted = last_stamp_.index == last_trusted_stamp_.index ? 0.0 : framesBetween(last_trusted_stamp_, last_stamp_);
  const double left = std::max(0.0, static_cast<double>(kMaxDeadReckoning) - since_trusted);
  return std::min(framesBetween(last_stamp_, stampOf(frame)), left);
}

Eigen::Isometry3d Odometry::frameMotion() const {
  if (poses_seen_ < 2) return Eigen::Isometry3d::Identity();
  const Eigen::Isometry3d motion = T_world_before_.inverse() * T_world_last_;
  const double frames = framesBetween(before_stamp_, last_stamp_);
  return frames == 1.0 ? motion : se3Exp(se3Log(motion) / frames);  // frames dropped between them: the mean
}

Eigen::Isometry3d Odometry::predict(const OdometryFrame& frame) const {
  const double frames = framesToExtrapolate(frame);
  if (frames == 1.0) return T_world_last_ * frameMotion();
  return T_world_last_ * se3Exp(frames * se3Log(frameMotion()));
}

Vector6d Odometry::drivingMotion(std::size_t newest) const {
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

}  // namespace semantic_edge_vo
