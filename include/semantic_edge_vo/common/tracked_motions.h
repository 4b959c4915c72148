#pragma once
#include <cstddef>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "semantic_edge_vo/common/pose_uncertainty.h"

namespace semantic_edge_vo {

/// A frame's pose as the tracker solved it against its keyframe, with the tracker's covariance (the
/// one nav_msgs/Odometry publishes): what evaluate_trajectory checks against ground truth.
struct TrackedMotion {
  std::size_t frame = 0, keyframe_frame = 0;  ///< frame numbers of the sequence
  bool in_metres = false;                     ///< the map's scale came from the road when it was tracked
  Eigen::Isometry3d T_cam_kf = Eigen::Isometry3d::Identity();
  Matrix6d covariance = Matrix6d::Zero();  ///< of xi in T_cam_kf = exp(xi) * T_cam_kf, (v, w), camera axes
};

/// tracked_motions.txt: a '#' header, then one motion a line: frame, keyframe_frame, in_metres (0/1),
/// T_cam_kf row-major 3x4 (12 numbers), the covariance's upper triangle row by row (21 numbers).
std::string writeTrackedMotions(const std::string& path, const std::vector<TrackedMotion>& motions);
/// Empty on success (a file of no motions too), otherwise "<path>:<line>: what is wrong" (motions unchanged).
std::string readTrackedMotions(const std::string& path, std::vector<TrackedMotion>* motions);

}  // namespace semantic_edge_vo
