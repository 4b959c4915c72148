#pragma once
#include <string>

#include <Eigen/Geometry>

namespace tf2_ros {
class Buffer;
}  // namespace tf2_ros

namespace semantic_edge_vo {

/// The camera's pose on the vehicle, T_base_cam (maps points from the camera optical frame to base_link).
struct CameraMounting {
  Eigen::Isometry3d T_base_cam = Eigen::Isometry3d::Identity();
  bool from_tf = false;
  /// What was assumed, for one warning: the optical default in place of tf, or a camera frame that
  /// does not look optical (empty: nothing).
  std::string assumption;
};

/// base_link -> `camera_frame` from tf, waiting up to `wait` s for it; without it, the optical
/// default (opticalDefault), and the assumption said.
CameraMounting resolveCameraMounting(const tf2_ros::Buffer& tf, const std::string& base_frame, const std::string& camera_frame,
                                     double wait);

/// The pure optical rotation at base_link's origin: camera z forward = base x, camera x right =
/// -base y, camera y down = -base z (a forward-facing camera).
Eigen::Isometry3d opticalDefault();

/// Why a camera frame with this rotation in base_link does not look like an optical frame (z
/// forward, x right, y down, REP-103): its y axis does not point down. Empty when it does.
std::string opticalFrameDoubt(const Eigen::Matrix3d& R_base_cam);

/// The parent `child` has on tf other than `parent` (empty: none, or that one): publishing parent
/// -> child then would give it two parents.
std::string otherParentOnTf(const tf2_ros::Buffer& tf, const std::string& child, const std::string& parent);

/// Odometry is estimated in "world", the optical frame of the first camera. The odom frame is base_link
/// at that moment (REP-105), so T_odom_world = T_base_cam, and base_link in odom is
/// T_odom_base = T_base_cam * T_world_cam * T_base_cam^-1.
inline Eigen::Isometry3d baseInOdom(const Eigen::Isometry3d& T_world_cam, const Eigen::Isometry3d& T_base_cam) {
  return T_base_cam * T_world_cam * T_base_cam.inverse();
}

}  // namespace semantic_edge_vo
