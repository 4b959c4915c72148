// Odometry: new keyframes, their points and the windowed optimisation.
#include <algorithm>
#include <chrono>
#include <cmath>

#include "odometry_detail.h"
#include "semantic_edge_vo/backend/odometry.h"
#include "semantic_edge_vo/common/parallel_slices.h"
#include "semantic_edge_vo/common/robust_statistics.h"

namespace semantic_edge_vo {

using odometry_detail::elapsedMs;



std::shared_ptr<const SharedClassEdgeTest> Odometry::refineDepths(const OdometryFrame& frame, const Eigen::Isometry3d& T_frame_kf) {
  std::shared_ptr<const SharedClassEdgeTest> edges = depths_.refine(active_.get(), frame, T_frame_kf);
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
  pose->window_correction = keyframe->T_world_cam * pose->T_world_cam.inverse();
  pose->T_world_cam = keyframe->T_world_cam;
  return true;
}

double Odometry::triangulatePoints(Keyframe* keyframe, const Keyframe& previous) const {
  takeCandidates(keyframe);
  return depths_.triangulate(keyframe, previous);
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
