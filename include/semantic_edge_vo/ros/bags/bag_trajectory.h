#pragma once
#include <string>

#include <Eigen/Geometry>

#include "semantic_edge_vo/common/trajectory_io.h"

namespace semantic_edge_vo {

/// Reads the nav_msgs/Odometry messages of `topic` in a bag as a camera trajectory stamped with
/// their header stamps (seconds). The odometry nodelet publishes base_link in odom,
/// T_odom_base = T_base_cam * T_world_cam * T_base_cam^-1 (camera_extrinsic.h), so each pose is
/// turned back into T_world_cam = T_base_cam^-1 * T_odom_base * T_base_cam, the world being the
/// first camera's optical frame as in KITTI ground truth.
/// @param[in] T_base_cam the camera's pose on the vehicle the odometry ran with
/// @return empty on success, otherwise what is wrong (naming the bag, the topic or the message)
std::string readOdometryBag(const std::string& path, const std::string& topic, const Eigen::Isometry3d& T_base_cam,
                            Trajectory* trajectory);

}  // namespace semantic_edge_vo
