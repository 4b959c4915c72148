#pragma once
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "semantic_edge_vo/synthetic/ego_motion.h"
#include "semantic_edge_vo/synthetic/road_profile.h"
#include "semantic_edge_vo/synthetic/route.h"
#include "semantic_edge_vo/synthetic/scene_geometry.h"
#include "semantic_edge_vo/synthetic/scene_type.h"
#include "semantic_edge_vo/synthetic/traffic.h"

namespace semantic_edge_vo {
namespace synthetic {

/// The procedural world of one sequence: road, roadside, traffic and the camera car's motion.
struct WorldOptions {
  SceneType scene = SceneType::kCity;
  std::uint64_t seed = 1;
  double render_distance = 250.0;  ///< geometry farther along the route is left out, m
  bool traffic = true;             ///< moving vehicles
  RouteOptions route;              ///< defaults of the scene type: see forScene()
  EgoMotionOptions ego;

  /// The defaults of a scene type: city turns at 30-70 m radius and 5-12 m/s, village curves and
  /// 6-14 m/s, highway gentle bends and 17-25 m/s.
  static WorldOptions forScene(SceneType scene);
  std::string validate() const;
};

class World {
 public:
  static constexpr double kChunkLength = 40.0;  ///< m of route furnished at a time

  explicit World(const WorldOptions& options);
  World(const World&) = delete;  // the trajectory points at the route
  World& operator=(const World&) = delete;

  const WorldOptions& options() const { return options_; }
  const RoadProfile& road() const { return road_; }
  /// The camera car at frame i (frames in any order).
  const EgoState& ego(int frame) { return trajectory_.frame(frame); }
  /// The polygons (map frame) that may be visible at frame i: the roadside near the camera, the
  /// ground, the moving vehicles. Valid until the next call.
  const std::vector<const Polygon*>& gather(int frame);

 private:
  const Polygons& chunk(long long index);

  WorldOptions options_;
  RoadProfile road_;
  Route route_;
  EgoTrajectory trajectory_;
  std::vector<TrafficLane> lanes_;
  std::map<long long, Polygons> chunks_;
  Polygons frame_polygons_;  // ground and vehicles of the current frame
  std::vector<const Polygon*> gathered_;
};

}  // namespace synthetic
}  // namespace semantic_edge_vo
