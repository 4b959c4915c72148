#include "semantic_edge_vo/backend/keyframe_depths.h"

#include <algorithm>
#include <cmath>

#include "semantic_edge_vo/common/parallel_slices.h"
#include "semantic_edge_vo/common/robust_statistics.h"

namespace semantic_edge_vo {
namespace {

std::shared_ptr<const SharedClassEdgeTest> edgeTestOf(const OdometryFrame& frame, double radius) {
  return frame.has_field ? std::make_shared<const SharedClassEdgeTest>(frame.field, radius) : nullptr;
}

// Samples bucketed in cells of `radius` px, so that those within radius of a pixel are found in the
// 3x3 cells around it.
class SampleGrid {
 public:
  SampleGrid(const std::vector<DepthSample>& samples, const PinholeCamera& camera, double radius)
      : samples_(samples),
        radius_(radius),
        cols_(static_cast<int>(std::ceil(camera.width / radius))),
        rows_(static_cast<int>(std::ceil(camera.height / radius))),
        cells_(static_cast<std::size_t>(cols_ * rows_)) {
    for (std::size_t i = 0; i < samples.size(); ++i) {
      const int cx = std::clamp(static_cast<int>(samples[i].pixel.x() / radius), 0, cols_ - 1);
      const int cy = std::clamp(static_cast<int>(samples[i].pixel.y() / radius), 0, rows_ - 1);
      cells_[static_cast<std::size_t>(cy * cols_ + cx)].push_back(i);
    }
  }

  /// Calls visit(sample index, distance px) for each sample within the radius of (u, v).
  template <typename Visit>
  void forEachNear(float u, float v, Visit visit) const {
    const Eigen::Vector2d pixel(u, v);
    const int cx = static_cast<int>(u / radius_), cy = static_cast<int>(v / radius_);
    for (int y = std::max(0, cy - 1); y <= std::min(rows_ - 1, cy + 1); ++y)
      for (int x = std::max(0, cx - 1); x <= std::min(cols_ - 1, cx + 1); ++x)
        for (std::size_t i : cells_[static_cast<std::size_t>(y * cols_ + x)]) {
          const double distance = (samples_[i].pixel - pixel).norm();
          if (distance <= radius_) visit(i, distance);
        }
  }

 private:
  const std::vector<DepthSample>& samples_;
  double radius_;
  int cols_, rows_;
  std::vector<std::vector<std::size_t>> cells_;
};

// The points each take the depth of the nearest sample within radius px as if measured (one
// observation, the sample's variance); the others get none.
std::vector<MapPoint> adoptNearest(const std::vector<DepthSample>& samples, const std::vector<double>& variances,
                                   const PinholeCamera& camera, double radius, std::vector<MapPoint> points) {
  const SampleGrid grid(samples, camera, radius);
  for (MapPoint& point : points) {
    point.observations = 0;
    point.inverse_depth = 0.0;
    double nearest = radius;
    grid.forEachNear(point.u, point.v, [&](std::size_t i, double distance) {
      if (distance > nearest) return;
      nearest = distance;
      point.inverse_depth = samples[i].inverse_depth;
      point.inverse_depth_variance = variances[i];
      point.observations = 1;
    });
  }
  return points;
}

}  // namespace

void KeyframeDepths::propagate(const std::vector<DepthSample>& samples, std::vector<MapPoint>* points) const {
  const SampleGrid grid(samples, camera_, neighbour_radius_);
  std::vector<double> all;
  for (const DepthSample& sample : samples) all.push_back(sample.inverse_depth);
  const double fallback = all.empty() ? default_inverse_depth_ : median(all);
  std::vector<double> near;
  for (MapPoint& point : *points) {
    if (point.hasDepth()) continue;
    near.clear();
    grid.forEachNear(point.u, point.v, [&](std::size_t i, double) { near.push_back(samples[i].inverse_depth); });
    point.inverse_depth = near.empty() ? fallback : median(near);
    point.inverse_depth_variance = std::pow((near.empty() ? 1.0 : 0.5) * point.inverse_depth, 2);
    point.observations = 0;
  }
}

double KeyframeDepths::triangulate(Keyframe* keyframe, const Keyframe& previous, std::vector<MapPoint>* map_depths) const {
  // Prior depths: the previous keyframe's measured points, seen from the new keyframe.
  const Eigen::Isometry3d T_new_old = keyframe->T_world_cam.inverse() * previous.T_world_cam;
  std::vector<DepthSample> samples;
  std::vector<double> variances;
  for (const MapPoint& point : previous.points) {
    if (!point.hasDepth()) continue;
    const Eigen::Vector3d p = T_new_old * camera_.backProject(point.u, point.v, 1.0 / point.inverse_depth);
    const Eigen::Vector2d pixel = camera_.project(p);
    if (p.z() > 1e-3 && camera_.contains(pixel.x(), pixel.y())) {
      samples.push_back({pixel, 1.0 / p.z()});
      // The same relative variance at the new depth.
      variances.push_back(point.inverse_depth_variance * std::pow(1.0 / (p.z() * point.inverse_depth), 2));
    }
  }
  constexpr double kMapDepthRadius = 2.0;  // px: an edge's neighbour across it is another surface
  if (map_depths) *map_depths = adoptNearest(samples, variances, camera_, kMapDepthRadius, keyframe->points);
  propagate(samples, &keyframe->points);
  std::vector<double> priors(keyframe->points.size(), 0.0);  // of the points with map points near
  for (std::size_t i = 0; i < priors.size(); ++i)
    if (keyframe->points[i].inverse_depth_variance < std::pow(0.75 * keyframe->points[i].inverse_depth, 2)) priors[i] = keyframe->points[i].inverse_depth;
  const PyramidLevel& host = keyframe->frame->pyramid->level(0);
  const std::shared_ptr<const SharedClassEdgeTest> previous_edges =
      previous.edge_test ? previous.edge_test : edgeTestOf(*previous.frame, epipolar_.edge_radius);
  measure(host, {&previous.frame->pyramid->level(0), previous_edges.get(), T_new_old.inverse()}, &keyframe->points);
  std::vector<double> ratios;  // inverse depths measured over the map's
  for (std::size_t i = 0; i < priors.size(); ++i)
    if (priors[i] > 0.0 && keyframe->points[i].observations > 0) ratios.push_back(keyframe->points[i].inverse_depth / priors[i]);
  constexpr std::size_t kMinRatios = 20;  // fewer: no say on the scale
  return ratios.size() < kMinRatios ? 1.0 : 1.0 / median(ratios);
}

std::shared_ptr<const SharedClassEdgeTest> KeyframeDepths::refine(Keyframe* keyframe, const OdometryFrame& frame,
                                                                   const Eigen::Isometry3d& T_frame_kf) const {
  std::shared_ptr<const SharedClassEdgeTest> edges = edgeTestOf(frame, epipolar_.edge_radius);
  measure(keyframe->frame->pyramid->level(0), {&frame.pyramid->level(0), edges.get(), T_frame_kf}, &keyframe->points);
  return edges;
}

void KeyframeDepths::measure(const PyramidLevel& host, const EpipolarTarget& target, std::vector<MapPoint>* points) const {
  // Each point is searched and filtered on its own: both cores, same result as in order.
  forEachIndex(points->size(), [&](std::size_t i) {
    DepthMeasurement measurement;
    MapPoint& point = (*points)[i];
    if (searchEpipolar(point, host, *target.level, target.edges, target.T_target_host, epipolar_, &measurement))
      fuseDepth(measurement, &point);
  });
}

}  // namespace semantic_edge_vo
