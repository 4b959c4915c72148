#include "semantic_edge_vo/synthetic/traffic.h"

#include <algorithm>
#include <cmath>

#include "semantic_edge_vo/synthetic/noise.h"
#include "semantic_edge_vo/synthetic/props.h"
#include "semantic_edge_vo/synthetic/random.h"

namespace semantic_edge_vo {
namespace synthetic {
namespace {

constexpr double kSlot = 25.0;  // m between possible vehicles of a lane
constexpr double kPi = 3.141592653589793;

void addVehicle(Route* route, double s, double offset, int direction, bool truck, std::uint32_t variant, Polygons* out) {
  const RoutePoint point = route->at(s);
  const Eigen::Isometry3d pose =
      groundPose(point.position + offset * point.right, point.heading + (direction < 0 ? kPi : 0.0));
  const std::size_t first = out->size();
  if (truck) addTruck(out, pose, variant);
  else addCar(out, pose, variant);
  for (std::size_t i = first; i < out->size(); ++i) (*out)[i].dynamic = true;
}

}  // namespace

std::vector<TrafficLane> trafficLanes(SceneType type, const RoadProfile& road) {
  switch (type) {
    case SceneType::kCity: return {{road.oncoming_lane_offset, -1, 9.0, 0.35, 0.1}};
    case SceneType::kVillage: return {{road.oncoming_lane_offset, -1, 11.0, 0.12, 0.15}};
    case SceneType::kHighway: {
      const double lane = road.lane_width, inner = 1.5 + 0.5 * lane;
      return {{inner, 1, 31.0, 0.25, 0.0},
              {inner + 2.0 * lane, 1, 21.0, 0.3, 0.5},
              {-inner, -1, 30.0, 0.25, 0.0},
              {-(inner + lane), -1, 26.0, 0.25, 0.2},
              {-(inner + 2.0 * lane), -1, 22.0, 0.3, 0.5}};
    }
  }
  return {};
}

void addTraffic(const std::vector<TrafficLane>& lanes, Route* route, double time, double s_from, double s_to,
                std::uint64_t seed, Polygons* out) {
  for (std::size_t l = 0; l < lanes.size(); ++l) {
    const TrafficLane& lane = lanes[l];
    const double shift = lane.direction * lane.speed * time;  // s = s0 + shift
    const auto first = static_cast<long long>(std::floor((s_from - shift) / kSlot));
    const auto last = static_cast<long long>(std::ceil((s_to - shift) / kSlot));
    for (long long slot = first; slot <= last; ++slot) {
      Random random(hashCombine(seed, hashCombine(l, static_cast<std::uint64_t>(slot))));
      if (!random.chance(lane.occupancy)) continue;
      const bool truck = random.chance(lane.truck_fraction);
      const double s = slot * kSlot + random.uniform(0.0, kSlot - (truck ? 13.0 : 5.0)) + shift;
      if (s < 0.0 || s < s_from || s > s_to) continue;
      addVehicle(route, s, lane.offset, lane.direction, truck, static_cast<std::uint32_t>(random.next()), out);
    }
  }
}

void addLeadVehicle(Route* route, double lane_offset, double s_ego, double time, std::uint64_t seed, Polygons* out) {
  const auto seed32 = static_cast<std::uint32_t>(seed);
  // Present while a slow noise is low; otherwise it has pulled away far beyond the view.
  const double away = std::clamp((valueNoise1d(time / 25.0, seed32 ^ 0x5151u) - 0.45) * 5.0, 0.0, 1.0);
  const double gap = 14.0 + 12.0 * valueNoise1d(time / 6.0, seed32 ^ 0x6161u) + 500.0 * away * away * (3.0 - 2.0 * away);
  if (gap > 400.0) return;
  addVehicle(route, s_ego + gap, lane_offset, 1, false, static_cast<std::uint32_t>(hashCombine(seed, 0x1ead)), out);
}

}  // namespace synthetic
}  // namespace semantic_edge_vo
