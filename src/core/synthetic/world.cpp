#include "semantic_edge_vo/synthetic/world.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "semantic_edge_vo/synthetic/scene_layout.h"

namespace semantic_edge_vo {
namespace synthetic {

WorldOptions WorldOptions::forScene(SceneType scene) {
  WorldOptions options;
  options.scene = scene;
  const RoadProfile road = roadProfile(scene);
  options.ego.lane_offset = road.ego_lane_offset;
  switch (scene) {
    case SceneType::kCity: break;  // the RouteOptions and EgoMotionOptions defaults
    case SceneType::kVillage:
      options.route = {20.0, 90.0, 40.0, 140.0, 0.2, 0.9, 15.0, 1.3};
      options.ego.min_speed = 6.0;
      options.ego.max_speed = 14.0;
      break;
    case SceneType::kHighway:
      options.route = {150.0, 500.0, 500.0, 1400.0, 0.1, 0.45, 80.0, 1.2};
      options.ego.min_speed = 17.0;
      options.ego.max_speed = 25.0;
      options.ego.speed_block = 400.0;
      options.ego.max_acceleration = 1.0;
      options.ego.vibration = 0.001;
      break;
  }
  return options;
}

std::string WorldOptions::validate() const {
  std::ostringstream error;
  if (!(render_distance >= 20.0)) error << "render_distance must be >= 20 m (got " << render_distance << ")";
  else if (const std::string route_error = route.validate(); !route_error.empty()) error << "route: " << route_error;
  else if (const std::string ego_error = ego.validate(); !ego_error.empty()) error << "ego: " << ego_error;
  return error.str();
}

World::World(const WorldOptions& options)
    : options_(options),
      road_(roadProfile(options.scene)),
      route_(options.route, options.seed),
      trajectory_(options.ego, &route_, hashCombine(options.seed, 0x65676fULL)),
      lanes_(trafficLanes(options.scene, road_)) {}

const Polygons& World::chunk(long long index) {
  auto found = chunks_.find(index);
  if (found != chunks_.end()) return found->second;
  const double s0 = static_cast<double>(index) * kChunkLength;
  route_.ensureLength(s0 + kChunkLength + 400.0);  // the keep-out test looks this far ahead
  Polygons& polygons = chunks_[index];
  const std::uint64_t seed = hashCombine(options_.seed, static_cast<std::uint64_t>(index) * 4 + static_cast<std::uint64_t>(options_.scene));
  ChunkContext context(route_, road_, s0, s0 + kChunkLength, seed, &polygons);
  buildRoadSurface(&context, options_.scene);
  switch (options_.scene) {
    case SceneType::kCity: buildCityChunk(&context); break;
    case SceneType::kVillage: buildVillageChunk(&context); break;
    case SceneType::kHighway: buildHighwayChunk(&context); break;
  }
  return polygons;
}

const std::vector<const Polygon*>& World::gather(int frame) {
  const EgoState& state = trajectory_.frame(frame);
  const auto first = static_cast<long long>(std::floor((state.s - 30.0) / kChunkLength));
  const auto last = static_cast<long long>(std::floor((state.s + options_.render_distance) / kChunkLength));
  // Chunks behind the camera are not needed again when frames go forward; rebuilding is cheap.
  chunks_.erase(chunks_.begin(), chunks_.lower_bound(first));
  chunks_.erase(chunks_.upper_bound(last), chunks_.end());

  frame_polygons_.clear();
  // The ground: a large grass plane 3 cm below the road surface, under everything else.
  const Eigen::Vector3d centre = state.T_map_cam.translation();
  const double half = 3000.0, y = 0.03;
  addPolygon(&frame_polygons_,
             {Eigen::Vector3d(centre.x() - half, y, centre.z() - half), Eigen::Vector3d(centre.x() + half, y, centre.z() - half),
              Eigen::Vector3d(centre.x() + half, y, centre.z() + half), Eigen::Vector3d(centre.x() - half, y, centre.z() + half)},
             up(), {Material::kGrass, 9, 0, false}, Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitX(),
             Eigen::Vector3d::UnitZ());
  if (options_.traffic) {
    addTraffic(lanes_, &route_, state.time, state.s - 30.0, state.s + options_.render_distance,
               hashCombine(options_.seed, 0x747266ULL), &frame_polygons_);
    addLeadVehicle(&route_, road_.ego_lane_offset, state.s, state.time, hashCombine(options_.seed, 0x6c656164ULL),
                   &frame_polygons_);
  }
  gathered_.clear();
  for (long long index = std::max(0LL, first); index <= last; ++index)
    for (const Polygon& polygon : chunk(index)) gathered_.push_back(&polygon);
  for (const Polygon& polygon : frame_polygons_) gathered_.push_back(&polygon);
  return gathered_;
}

}  // namespace synthetic
}  // namespace semantic_edge_vo
