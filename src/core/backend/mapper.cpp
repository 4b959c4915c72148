// Mapper: depths refined by each tracked frame, keyframe decisions, new keyframes and the window.
#include "semantic_edge_vo/backend/mapper.h"

#include <chrono>
#include <cmath>

#include "odometry_detail.h"
#include "semantic_edge_vo/backend/dense_road_fit.h"
#include "semantic_edge_vo/common/freed_memory.h"
#include "semantic_edge_vo/common/robust_statistics.h"
#include "semantic_edge_vo/common/se3.h"

namespace semantic_edge_vo {

using odometry_detail::elapsedMs;
using odometry_detail::gray8;

Mapper::Mapper(const OdometryOptions& options, const PinholeCamera& camera)
    : options_(options),
      camera_(camera),
      depths_(options.epipolar, camera, options.depth_neighbour_radius, 1.0 / options.initializer.median_depth),
      window_optimizer_(options.window_optimizer, options.road),
      keyframe_motion_(options.keyframe_motion, camera),
      class_reliability_(options.class_reliability) {}

void Mapper::startMap(const MappingRequest& request) {
  auto keyframe = std::make_shared<Keyframe>();
  keyframe->id = next_keyframe_id_++;
  keyframe->T_world_cam = request.T_world_cam;
  keyframe->frame = request.frame;
  takeCandidates(keyframe.get());
  const std::vector<double>& inverse_depths = request.inverse_depths;
  for (std::size_t i = 0; i < keyframe->points.size() && i < inverse_depths.size(); ++i) {
    if (!(inverse_depths[i] > 0.0)) continue;
    MapPoint& point = keyframe->points[i];
    point.inverse_depth = inverse_depths[i];
    point.inverse_depth_variance = std::pow(0.1 * point.inverse_depth, 2);
    point.observations = 1;
  }
  std::vector<DepthSample> samples;
  for (const MapPoint& point : keyframe->points)
    if (point.hasDepth()) samples.push_back({Eigen::Vector2d(point.u, point.v), point.inverse_depth});
  depths_.propagate(samples, &keyframe->points);
  keyframes_.push_back(keyframe);
  setActiveKeyframe(keyframe);
  frames_since_keyframe_ = 0;
  scale_measured_ = false;
  frame_road_heights_.clear();
  previous_frame_ = request.frame;
  previous_T_world_cam_ = request.T_world_cam;
}

MappingOutcome Mapper::map(const MappingRequest& request) {
  const auto start = std::chrono::steady_clock::now();
  MappingOutcome outcome;
  outcome.frame_index = request.frame->index;
  if (request.tuning) request.tuning->applyTo(&options_);
  if (request.new_map) {
    startMap(request);
    outcome.T_world_cam = request.T_world_cam;
    outcome.window = window();
  } else if (!refineWith(request, &outcome)) {
    outcome.stale = true;
    return outcome;
  }
  outcome.active = std::make_shared<const Keyframe>(*active_);
  outcome.keyframe_poses = keyframePoses();
  outcome.mapping_ms = elapsedMs(start);
  return outcome;
}

bool Mapper::refineWith(const MappingRequest& request, MappingOutcome* outcome) {
  const Keyframe* tracked_against = active_ ? keyframeWithId(request.keyframe_id) : nullptr;
  if (!tracked_against) return false;
  // Where the window has the keyframe it was tracked against now, the frame is (parallel mapping:
  // the window may have moved it since tracking took its copy).
  outcome->T_world_cam = orthonormalized(tracked_against->T_world_cam * request.tracking.T_cam_kf.inverse());
  const bool tracked_against_active = tracked_against == active_.get();
  const Eigen::Isometry3d T_cam_kf =
      tracked_against_active ? request.tracking.T_cam_kf : outcome->T_world_cam.inverse() * active_->T_world_cam;
  const OdometryFrame& frame = *request.frame;
  std::shared_ptr<const SharedClassEdgeTest> frame_edges = depths_.refine(active_.get(), frame, T_cam_kf);
  if (keyframe_motion_.enabled()) keyframe_motion_.follow(frame.index, gray8(frame));
  ++frames_since_keyframe_;
  const bool first_against_active = tracked_against_active && !first_inlier_ratio_;
  if (first_against_active) first_inlier_ratio_ = request.tracking.inlierRatio();
  // A frame tracked against an older keyframe (parallel mapping made this one meanwhile) measures
  // the new keyframe's depths too (they have a single observation so far), but its flow and points
  // in view were another keyframe's: the decision waits for the frames tracked against this one.
  const Eigen::Isometry3d T_world_frame = outcome->T_world_cam;  // as tracked (a keyframe's moves in the window)
  const bool keyframe_wanted =
      tracked_against_active && !request.waited_for_initialization && wantsKeyframe(request, first_against_active);
  // Every frame's road until the map's scale is set (its first scale sooner, from the frames that
  // wait for the initialisation on), then a keyframe's.
  const RoadFit road = keyframe_wanted || !scale_measured_ ? measureRoad(frame, T_world_frame) : RoadFit();
  if (tracked_against_active && !request.waited_for_initialization) {
    if (frame.has_field && frame.classes_known) class_reliability_.observe(*active_, T_cam_kf, frame.field);
    if (keyframe_wanted) makeKeyframe(request, outcome->T_world_cam, std::move(frame_edges), road, outcome);
  }
  if (!outcome->keyframe && !outcome->refused && !scale_measured_ && road.found) {
    frame_road_heights_.push_back(road.height);
    // The frames that waited for the initialisation have no pose out yet: about the map's first
    // keyframe (the active one then), the map keeps its origin. Later ones: about the frame, so
    // odom does not jump.
    outcome->rescaled_about = (request.waited_for_initialization ? active_->T_world_cam : T_world_frame).translation();
    outcome->map_rescale = measureMapScale(outcome->rescaled_about);
  }
  previous_frame_ = request.frame;
  previous_T_world_cam_ = T_world_frame;
  if (outcome->map_rescale != 1.0) {  // the frame's poses, at the map's new scale
    scaleAbout(outcome->map_rescale, outcome->rescaled_about, &previous_T_world_cam_);
    if (!outcome->keyframe) outcome->T_world_cam = previous_T_world_cam_;
  }
  return true;
}

const Keyframe* Mapper::keyframeWithId(int id) const {
  if (active_ && active_->id == id) return active_.get();
  for (const auto& keyframe : keyframes_)
    if (keyframe->id == id) return keyframe.get();
  return nullptr;
}

std::map<int, Eigen::Isometry3d> Mapper::keyframePoses() const {
  std::map<int, Eigen::Isometry3d> poses;
  for (const auto& keyframe : keyframes_) poses[keyframe->id] = keyframe->T_world_cam;
  if (active_) poses[active_->id] = active_->T_world_cam;
  return poses;
}

bool Mapper::wantsKeyframe(const MappingRequest& request, bool first_against_active) const {
  const TrackingResult& tracking = request.tracking;
  const bool few_in_view = tracking.points_in_view < options_.keyframe_min_in_view * tracking.points;
  // The interval only while the camera travels: standing, a keyframe would measure no depth.
  const bool interval = frames_since_keyframe_ >= options_.keyframe_max_interval &&
                        travelParallax(tracking.T_cam_kf) >= options_.keyframe_min_parallax;
  const bool faded = !first_against_active && first_inlier_ratio_ &&
                     tracking.inlierRatio() < options_.keyframe_min_inliers * *first_inlier_ratio_;
  return tracking.mean_flow > options_.keyframe_flow || few_in_view || interval || faded;
}

double Mapper::travelParallax(const Eigen::Isometry3d& T_frame_kf) const {
  std::vector<double> flows;
  for (const MapPoint& point : active_->points) {
    if (!point.hasDepth()) continue;
    const Eigen::Vector3d p = camera_.backProject(point.u, point.v, 1.0 / point.inverse_depth);
    const Eigen::Vector3d rotated = T_frame_kf.linear() * p, moved = rotated + T_frame_kf.translation();
    if (rotated.z() <= 1e-3 || moved.z() <= 1e-3) continue;
    flows.push_back((camera_.project(moved) - camera_.project(rotated)).norm());
  }
  return median(flows);
}

void Mapper::makeKeyframe(const MappingRequest& request, const Eigen::Isometry3d& T_world_cam,
                          std::shared_ptr<const SharedClassEdgeTest> frame_edges, const RoadFit& road, MappingOutcome* outcome) {
  auto keyframe = std::make_shared<Keyframe>();
  keyframe->T_world_cam = T_world_cam;
  keyframe->frame = request.frame;
  // Its points triangulated from the tracked pose must see the map at the map's scale: a keyframe
  // whose depths disagree with it by more than the bound would hand the next frames a new scale.
  std::vector<MapPoint> map_depths;  // of the points the map's measured points fall on
  outcome->keyframe_scale = triangulatePoints(keyframe.get(), *active_, &map_depths);
  if (std::abs(std::log(outcome->keyframe_scale)) > std::log1p(options_.consistency.max_keyframe_scale_change)) {
    outcome->refused = true;
    return;
  }
  keyframe->id = next_keyframe_id_++;
  if (on_provisional_) {
    MappingOutcome provisional;
    provisional.frame_index = request.frame->index;
    provisional.provisional = true;
    // Its points carry the map's depths, not those just triangulated: those agree with the tracked
    // pose's error, and the frames tracked against them would carry it on (their inlier ratios fall).
    keyframe->points = std::move(map_depths);
    provisional.active = std::make_shared<const Keyframe>(*keyframe);
    provisional.T_world_cam = T_world_cam;
    provisional.keyframe_poses = keyframePoses();
    provisional.keyframe_poses[keyframe->id] = T_world_cam;
    on_provisional_(std::move(provisional));
  }
  // Its points join once the window has settled its pose (below), not before: points triangulated
  // from the tracked pose agree with its error and would pin it there (a yaw error leaves a
  // left-right depth gradient that makes the next yaw error).
  keyframe->points.clear();
  keyframe->edge_test = std::move(frame_edges);
  keyframe->road = road;
  keyframe->measured_motion =
      keyframe_motion_.measure(request.frame->index, (active_->T_world_cam.inverse() * keyframe->T_world_cam).linear());
  reanchor(keyframe->measured_motion, options_.keyframe_motion, active_->T_world_cam, &keyframe->T_world_cam);
  keyframes_.push_back(keyframe);
  while (static_cast<int>(keyframes_.size()) > options_.window_size) {
    keyframes_.pop_front();
    if (++keyframes_left_ % kKeyframesBetweenTrims == 0) releaseFreedMemory();  // frames freed between bursts
  }
  outcome->rescaled_about = T_world_cam.translation();
  outcome->map_rescale = measureMapScale(outcome->rescaled_about);
  if (options_.optimize_window) {
    const auto start = std::chrono::steady_clock::now();
    const WindowOptimizerResult solved = window_optimizer_.optimize(keyframes_, stop_window_);
    outcome->window_ms = elapsedMs(start);
    outcome->window_keyframes = solved.keyframes;
    outcome->road_keyframes = solved.road_keyframes;
  }
  triangulatePoints(keyframe.get(), *active_);
  setActiveKeyframe(keyframe);
  frames_since_keyframe_ = 0;
  outcome->keyframe = true;
  outcome->window_correction = keyframe->T_world_cam * T_world_cam.inverse();
  outcome->T_world_cam = keyframe->T_world_cam;
  outcome->window = window();
}

double Mapper::triangulatePoints(Keyframe* keyframe, const Keyframe& previous, std::vector<MapPoint>* map_depths) const {
  takeCandidates(keyframe);
  return depths_.triangulate(keyframe, previous, map_depths);
}

void Mapper::takeCandidates(Keyframe* keyframe) const {
  keyframe->points = keyframe->frame->candidates;
  const int all_edges_layer = keyframe->frame->has_field ? keyframe->frame->field.all_edges_layer : -1;
  for (MapPoint& point : keyframe->points)
    if (point.isEdge()) point.field_layers = class_reliability_.fieldLayers(point.class_mask, all_edges_layer);
}

RoadFit Mapper::measureRoad(const OdometryFrame& frame, const Eigen::Isometry3d& T_world_frame) const {
  // The frame before is the nearest view: over longer baselines the road's texture repeats (lane
  // markings) and its near part leaves the image.
  constexpr int kMaxFramesApart = 3;
  if (!options_.road.enabled() || !previous_frame_ || frame.index - previous_frame_->index > kMaxFramesApart) return RoadFit();
  // The camera rides at one height above the road: the last plane measured is the best guess;
  // before one, the active keyframe's points that may lie on the road.
  double guess = frame_road_heights_.empty() ? 0.0 : frame_road_heights_.back();
  for (auto it = keyframes_.rbegin(); it != keyframes_.rend() && !(guess > 0.0); ++it)
    if ((*it)->road.found) guess = (*it)->road.height;
  if (!(guess > 0.0)) {
    const RoadPlaneFinder finder(options_.road, camera_);
    const Eigen::Vector3d down = options_.road.expectedDown();
    std::vector<double> heights;
    for (const MapPoint& point : active_->points)
      if (point.hasDepth() && finder.isEvidence(point.u, point.v, point.class_mask))
        heights.push_back(down.dot(camera_.backProject(point.u, point.v, 1.0 / point.inverse_depth)));
    guess = median(heights);
  }
  if (!(guess > 0.0)) return RoadFit();
  const DenseRoadFitter fitter(options_.road, camera_);
  return fitter.fit(*frame.pyramid, *previous_frame_->pyramid, previous_T_world_cam_.inverse() * T_world_frame, guess);
}

double Mapper::measureMapScale(const Eigen::Vector3d& about) {
  if (!options_.road.enabled() || scale_measured_) return 1.0;
  const RoadPlaneFinder finder(options_.road, camera_);
  std::vector<double> heights = frame_road_heights_;
  for (const auto& keyframe : keyframes_) {
    const RoadFit fit = finder.fitKeyframe(*keyframe);
    if (fit.found) heights.push_back(fit.height);
  }
  // One fit may be a kerb or a verge: the scale is set once kMinRoadFits of them agree.
  const double middle = median(heights);
  std::vector<double> agreeing;
  for (double height : heights)
    if (std::abs(std::log(height / middle)) <= std::log1p(options_.road.max_height_change)) agreeing.push_back(height);
  if (static_cast<int>(agreeing.size()) < kMinRoadFits) return 1.0;
  scale_measured_ = true;
  frame_road_heights_.clear();
  const double scale = options_.road.camera_height / median(agreeing);
  for (const auto& keyframe : keyframes_) scaleAbout(scale, about, keyframe.get());
  return scale;
}

void Mapper::setActiveKeyframe(std::shared_ptr<Keyframe> keyframe) {
  active_ = std::move(keyframe);
  first_inlier_ratio_.reset();
  if (keyframe_motion_.enabled()) keyframe_motion_.start(active_->id, active_->frame->index, gray8(*active_->frame));
}

std::shared_ptr<const KeyframeWindow> Mapper::window() const {
  auto window = std::make_shared<KeyframeWindow>();
  window->frame_index = keyframes_.back()->frame->index;
  for (const auto& keyframe : keyframes_) window->keyframes.push_back(std::make_shared<const Keyframe>(*keyframe));
  return window;
}

}  // namespace semantic_edge_vo
