#pragma once
#include <memory>
#include <vector>

#include <Eigen/Geometry>

#include "semantic_edge_vo/backend/map_point.h"
#include "semantic_edge_vo/backend/road_plane.h"
#include "semantic_edge_vo/common/se3.h"
#include "semantic_edge_vo/frontend/odometry_frame.h"
#include "semantic_edge_vo/fields/shared_class_edge_test.h"

namespace semantic_edge_vo {

/// A keyframe's motion from the keyframe before it, measured by two-view geometry of corners
/// tracked between them: rotation and direction of travel, no scale.
struct MeasuredMotion {
  int from_id = -1;  ///< the keyframe it was measured from; -1: not measured
  Eigen::Matrix3d R_from_this = Eigen::Matrix3d::Identity();  ///< this keyframe's orientation in that one's optical frame
  Eigen::Vector3d direction = Eigen::Vector3d::UnitZ();      ///< unit direction to this keyframe's centre, same frame
};

struct Keyframe {
  int id = 0;
  Eigen::Isometry3d T_world_cam = Eigen::Isometry3d::Identity();  ///< camera-to-world
  std::shared_ptr<const OdometryFrame> frame;  ///< the frame it was made from (pyramid, field, index, time)
  std::vector<MapPoint> points;                ///< hosted points; those with observations > 0 have a measured depth
  MeasuredMotion measured_motion;
  /// Edges of the frame's field near each pixel, for epipolar searches into this keyframe: kept from
  /// when the frame was tracked (null: no field, or the frame was not searched into then).
  std::shared_ptr<const SharedClassEdgeTest> edge_test;
  /// The road plane under it, measured densely against the frame mapped before it (DenseRoadFitter)
  /// when it was made, in the map's units; not found: none (no camera height, or no road seen).
  RoadFit road;
};

/// The keyframe as part of a map scaled by `scale` about the world point `about`: its position and
/// its points' depths (and their variances), its road's height.
inline void scaleAbout(double scale, const Eigen::Vector3d& about, Keyframe* keyframe) {
  scaleAbout(scale, about, &keyframe->T_world_cam);
  keyframe->road.height *= scale;
  for (MapPoint& point : keyframe->points) {
    point.inverse_depth /= scale;
    point.inverse_depth_variance /= scale * scale;
  }
}

}  // namespace semantic_edge_vo
