// Odometry: depths of the active keyframe's points, new keyframes and the windowed optimisation.
#include <algorithm>
#include <chrono>
#include <cmath>

#include "odometry_detail.h"
#include "semantic_edge_vo/backend/odometry.h"
#include "semantic_edge_vo/common/parallel_slices.h"
#include "semantic_edge_vo/common/robust_statistics.h"

namespace semantic_edge_vo {
namespace {

std::shared_ptr<const SharedClassEdgeTest> edgeTestOf(const OdometryFrame& frame, double radius) {
  return frame.has_field ? std::make_shared<const SharedClassEdgeTest>(frame.field, radius) : nullptr;
}

}  // namespace

using odometry_detail::DepthSample;
using odometry_detail::elapsedMs;
using odometry_detail::propagateDepths;

void odometry_detail::propagateDepths(const std::vector<DepthSample>& samples, const PinholeCamera& camera, double radius,
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
  motion_.correct(correction);
  // The optimisation settled the active keyframe's pose without its points (see makeKeyframe), which
  // were triangulated from the tracked pose meanwhile: triangulate them again from the settled one.
  if (keyframes_.size() >= 2) triangulatePoints(active_.get(), *keyframes_[keyframes_.size() - 2]);
  return correction;
}

void Odometry::takeCandidates(Keyframe* keyframe) const {
  keyframe->points = keyframe->frame->candidates;
  const int all_edges_layer = keyframe->frame->has_field ? keyframe->frame->field.all_edges_layer : -1;
  for (MapPoint& point : keyframe->points)
    if (point.isEdge()) point.field_layers = class_reliability_.fieldLayers(point.class_mask, all_edges_layer);
}

}  // namespace semantic_edge_vo
