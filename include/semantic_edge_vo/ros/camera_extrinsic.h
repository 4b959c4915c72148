#pragma once
#include <memory>
#include <string>

#include <Eigen/Geometry>
#include <ros/time.h>

namespace tf2_ros {
class Buffer;
class TransformListener;
}  // namespace tf2_ros

namespace semantic_edge_vo {

/// The camera's pose on the vehicle, T_base_cam (maps points from the camera optical frame to
/// base_link). Taken from tf when a transform base_link -> camera frame exists; otherwise the pure
/// optical rotation (camera z forward = base x, camera x right = -base y, camera y down = -base z).
class CameraExtrinsic {
 public:
  CameraExtrinsic(std::string base_frame, double lookup_timeout_seconds);
  ~CameraExtrinsic();

  /// T_base_cam for `camera_frame`; looks tf up until it is found, then keeps it.
  /// @param[out] from_tf true when the transform came from tf, false for the default
  Eigen::Isometry3d baseFromCamera(const std::string& camera_frame, bool* from_tf = nullptr);

  static Eigen::Isometry3d opticalDefault();

 private:
  std::string base_frame_;
  double timeout_;
  std::unique_ptr<tf2_ros::Buffer> buffer_;
  std::unique_ptr<tf2_ros::TransformListener> listener_;
  std::string cached_frame_;
  Eigen::Isometry3d cached_ = Eigen::Isometry3d::Identity();
  bool cached_from_tf_ = false;
};

/// Odometry is estimated in "world", the optical frame of the first camera. The odom frame is base_link
/// at that moment (REP-105), so T_odom_world = T_base_cam, and base_link in odom is
/// T_odom_base = T_base_cam * T_world_cam * T_base_cam^-1.
inline Eigen::Isometry3d baseInOdom(const Eigen::Isometry3d& T_world_cam, const Eigen::Isometry3d& T_base_cam) {
  return T_base_cam * T_world_cam * T_base_cam.inverse();
}

}  // namespace semantic_edge_vo
