#pragma once
#include <vector>

#include "semantic_edge_vo/synthetic/scene_type.h"

namespace semantic_edge_vo {
namespace synthetic {

/// A painted line along the road. Offsets are lateral, from the centreline, positive to the right.
struct LaneLine {
  double offset = 0.0;  ///< centre of the line, m
  double width = 0.12;  ///< m
  double dash = 0.0;    ///< painted length of a dash, m (0: solid)
  double gap = 0.0;     ///< unpainted length between dashes, m
};

/// Cross-section of the road of a scene type.
struct RoadProfile {
  double paved_half_width = 3.0;    ///< asphalt from -this to +this, m
  double curb_height = 0.0;         ///< raised sidewalk height, m (0: no sidewalk)
  double sidewalk_width = 0.0;      ///< m
  double ego_lane_offset = 1.5;     ///< centre of the camera car's lane, m
  double oncoming_lane_offset = -1.5;  ///< centre of the nearest oncoming lane, m
  double lane_width = 3.0;          ///< m
  int lanes_per_direction = 1;
  std::vector<LaneLine> lines;

  /// Outer edge of the sidewalk (or of the asphalt without one), m.
  double builtHalfWidth() const { return paved_half_width + sidewalk_width; }
};

/// City: one lane each way plus parking lanes, curbs and sidewalks. Village: a narrow unmarked road.
/// Highway: three lanes each way around a median barrier, dashed lane lines.
RoadProfile roadProfile(SceneType type);

}  // namespace synthetic
}  // namespace semantic_edge_vo
