#include "semantic_edge_vo/synthetic/road_profile.h"

namespace semantic_edge_vo {
namespace synthetic {

RoadProfile roadProfile(SceneType type) {
  RoadProfile road;
  switch (type) {
    case SceneType::kCity:
      road.lane_width = 3.5;
      road.paved_half_width = 6.0;  // driving lane + 2.5 m parking lane
      road.curb_height = 0.15;
      road.sidewalk_width = 4.0;
      road.ego_lane_offset = 1.75;
      road.oncoming_lane_offset = -1.75;
      road.lines = {{0.0, 0.12, 3.0, 6.0}, {3.5, 0.12, 0.0, 0.0}, {-3.5, 0.12, 0.0, 0.0}};
      break;
    case SceneType::kVillage:
      road.lane_width = 2.75;
      road.paved_half_width = 2.75;
      road.ego_lane_offset = 1.4;
      road.oncoming_lane_offset = -1.4;
      break;
    case SceneType::kHighway: {
      // Median 1.5 m each side of the centreline, three 3.75 m lanes, a 3 m hard shoulder.
      road.lane_width = 3.75;
      road.lanes_per_direction = 3;
      road.paved_half_width = 1.5 + 3 * 3.75 + 3.0;
      road.ego_lane_offset = 1.5 + 1.5 * 3.75;  // the middle lane
      road.oncoming_lane_offset = -(1.5 + 2.5 * 3.75);
      for (double side : {-1.0, 1.0}) {
        road.lines.push_back({side * (1.5 + 0.1), 0.15, 0.0, 0.0});
        road.lines.push_back({side * (1.5 + 3.75), 0.15, 6.0, 12.0});
        road.lines.push_back({side * (1.5 + 7.5), 0.15, 6.0, 12.0});
        road.lines.push_back({side * (1.5 + 11.25), 0.2, 0.0, 0.0});
      }
      break;
    }
  }
  return road;
}

}  // namespace synthetic
}  // namespace semantic_edge_vo
