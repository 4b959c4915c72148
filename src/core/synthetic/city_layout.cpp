#include <algorithm>
#include <cmath>

#include "semantic_edge_vo/synthetic/props.h"
#include "semantic_edge_vo/synthetic/scene_layout.h"

namespace semantic_edge_vo {
namespace synthetic {
namespace {

constexpr double kPi = 3.141592653589793;

/// A row of buildings on one side, each within the chunk, with setbacks so neighbours never share a
/// facade plane.
void buildingRow(ChunkContext* chunk, double side) {
  Random& random = chunk->random;
  const double front = chunk->road.builtHalfWidth();
  double cursor = chunk->s0 + random.uniform(0.0, 2.0);
  while (true) {
    const bool curved = std::abs(chunk->route.at(cursor).curvature) > 0.005;
    const double length = random.uniform(8.0, curved ? 12.0 : 22.0);
    if (cursor + length > chunk->s1) break;
    if (random.chance(0.12)) {  // an alley or an empty lot
      cursor += random.uniform(3.0, 8.0);
      continue;
    }
    const double depth = random.uniform(10.0, 18.0);
    const double height = random.uniform(7.0, 24.0);
    const double setback = random.uniform(0.2, 2.0);
    const double s_mid = cursor + 0.5 * length;
    const Eigen::Isometry3d pose = chunk->poseAt(s_mid, side * (front + setback + 0.5 * depth));
    if (chunk->clearOfRoad(pose, depth, length)) addBuilding(chunk->out, pose, depth, height, length, chunk->variant());
    cursor += length + random.uniform(0.0, 0.6);
  }
}

}  // namespace

void buildCityChunk(ChunkContext* chunk) {
  Random& random = chunk->random;
  const RoadProfile& road = chunk->road;
  const double w = road.paved_half_width;
  for (double side : {-1.0, 1.0}) {
    buildingRow(chunk, side);
    // Parked cars in the parking lane, facing the traffic of their side.
    for (double s = chunk->s0 + random.uniform(0.0, 3.0); s < chunk->s1 - 3.0; s += random.uniform(5.5, 9.0)) {
      if (!random.chance(0.55)) continue;
      const double yaw = (side > 0 ? 0.0 : kPi) + random.uniform(-0.04, 0.04);
      addCar(chunk->out, chunk->poseAt(s, side * (w - 1.2 + random.uniform(-0.15, 0.15)), yaw), chunk->variant());
    }
    // Street lamps on the sidewalk edge, their arms over the road.
    for (double s = chunk->s0 + random.uniform(0.0, 10.0); s < chunk->s1; s += random.uniform(22.0, 32.0))
      addStreetLamp(chunk->out, chunk->poseAt(s, side * (w + 0.5), side > 0 ? 0.0 : kPi), random.uniform(6.0, 8.0));
    if (random.chance(0.5)) {
      const double s = random.uniform(chunk->s0, chunk->s1);
      const double size = random.uniform(0.5, 0.8);
      addSign(chunk->out, chunk->poseAt(s, side * (w + 0.7), side > 0 ? 0.0 : kPi), random.uniform(1.9, 2.5), size,
              size * random.uniform(0.8, 1.3), 1, chunk->variant());
    }
    if (random.chance(0.2)) {
      const double s = random.uniform(chunk->s0, chunk->s1);
      addTrafficLight(chunk->out, chunk->poseAt(s, side * (w + 0.6), side > 0 ? 0.0 : kPi), chunk->variant());
    }
    if (random.chance(0.3)) {
      const double s = random.uniform(chunk->s0, chunk->s1);
      addTree(chunk->out, chunk->poseAt(s, side * (w + 2.8), random.uniform(0.0, 6.28)), random.uniform(5.0, 9.0),
              random.uniform(1.5, 2.8), false, chunk->variant());
    }
    for (double s = chunk->s0 + random.uniform(0.0, 6.0); s < chunk->s1; s += random.uniform(4.0, 12.0))
      if (random.chance(0.3))  // bollards and sign posts without signs
        addPole(chunk->out, chunk->poseAt(s, side * (w + 0.35)), random.uniform(0.9, 2.8), 0.05, false);
  }
}

}  // namespace synthetic
}  // namespace semantic_edge_vo
