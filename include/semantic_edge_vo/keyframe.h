#pragma once
#include <memory>
#include <vector>

#include <Eigen/Geometry>

#include "semantic_edge_vo/map_point.h"
#include "semantic_edge_vo/odometry_frame.h"

namespace semantic_edge_vo {

struct Keyframe {
  int id = 0;
  Eigen::Isometry3d T_world_cam = Eigen::Isometry3d::Identity();  ///< camera-to-world
  std::shared_ptr<const OdometryFrame> frame;  ///< the frame it was made from (pyramid, field, index, time)
  std::vector<MapPoint> points;                ///< hosted points; those with observations > 0 have a measured depth
};

}  // namespace semantic_edge_vo
