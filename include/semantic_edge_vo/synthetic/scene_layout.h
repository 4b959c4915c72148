#pragma once
#include <cstdint>

#include <Eigen/Geometry>

#include "semantic_edge_vo/synthetic/random.h"
#include "semantic_edge_vo/synthetic/road_profile.h"
#include "semantic_edge_vo/synthetic/route.h"
#include "semantic_edge_vo/synthetic/scene_geometry.h"

namespace semantic_edge_vo {
namespace synthetic {

/// What a scene generator sees while it furnishes one stretch [s0, s1) of the route.
class ChunkContext {
 public:
  ChunkContext(const Route& route, const RoadProfile& road, double s0, double s1, std::uint64_t seed, Polygons* out)
      : route(route), road(road), s0(s0), s1(s1), random(seed), out(out) {}

  /// Pose of an object standing `offset` metres right of the centreline at arc length s, its z axis
  /// along the road (turned by `yaw`, rad).
  Eigen::Isometry3d poseAt(double s, double offset, double yaw = 0.0) const;
  /// True when every footprint corner of a width x length object (object frame x, z) at `pose` keeps
  /// `margin` metres beyond the built road (asphalt and sidewalks) of the whole route nearby: no
  /// building on the road on the inner side of a turn.
  bool clearOfRoad(const Eigen::Isometry3d& pose, double width, double length, double margin = 0.3) const;
  /// A quad strip along the road between arc lengths sa and sb, from (offset, height) `from` to `to`
  /// in the cross-section (m, height upwards). Horizontal strips are textured with a = lateral offset,
  /// b = arc length; the others with a = arc length, b = height.
  void addStrip(double sa, double sb, const Eigen::Vector2d& from, const Eigen::Vector2d& to,
                const Eigen::Vector3d& outward_hint, const Surface& surface);
  /// Object variant bits.
  std::uint32_t variant() { return static_cast<std::uint32_t>(random.next()); }

  const Route& route;
  const RoadProfile& road;
  const double s0, s1;
  Random random;
  Polygons* out;
};

/// Asphalt, curbs, sidewalks, median barrier and guard rails of [s0, s1) (all scene types).
void buildRoadSurface(ChunkContext* chunk, SceneType type);
/// Roadside of a city: building blocks, parked cars, lamps, signs, traffic lights, a few trees.
void buildCityChunk(ChunkContext* chunk);
/// Roadside of a village: trees, hedges, bushes, fences, a few houses, utility poles.
void buildVillageChunk(ChunkContext* chunk);
/// Roadside of a highway: guard rails, big signs, lamp posts, noise walls, sparse trees.
void buildHighwayChunk(ChunkContext* chunk);

}  // namespace synthetic
}  // namespace semantic_edge_vo
