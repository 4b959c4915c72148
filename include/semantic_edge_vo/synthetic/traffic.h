#pragma once
#include <cstdint>
#include <vector>

#include "semantic_edge_vo/synthetic/road_profile.h"
#include "semantic_edge_vo/synthetic/route.h"
#include "semantic_edge_vo/synthetic/scene_geometry.h"

namespace semantic_edge_vo {
namespace synthetic {

/// A lane of moving traffic: every vehicle in it drives at the same speed, so they never collide.
struct TrafficLane {
  double offset = 0.0;          ///< lane centre right of the centreline, m
  int direction = 1;            ///< +1 along the route, -1 oncoming
  double speed = 10.0;          ///< m/s
  double occupancy = 0.3;       ///< probability that a 25 m slot holds a vehicle
  double truck_fraction = 0.1;  ///< of the vehicles
};

/// The lanes with moving traffic of a scene type (the camera car's own lane has a lead vehicle instead).
std::vector<TrafficLane> trafficLanes(SceneType type, const RoadProfile& road);

/// Appends (map frame, marked dynamic) the vehicles of `lanes` whose arc length at `time` lies in
/// [s_from, s_to]. Vehicle k of a lane is at s = s0_k + direction * speed * time, with the s0_k fixed by
/// the seed, so traffic is deterministic and independent of the sequence length.
void addTraffic(const std::vector<TrafficLane>& lanes, Route* route, double time, double s_from, double s_to,
                std::uint64_t seed, Polygons* out);

/// Appends the vehicle ahead in the camera car's lane at `gap` metres; it drops back and pulls away
/// smoothly (gaps beyond the view make it disappear).
void addLeadVehicle(Route* route, double lane_offset, double s_ego, double time, std::uint64_t seed, Polygons* out);

}  // namespace synthetic
}  // namespace semantic_edge_vo
