#include "semantic_edge_vo/ros/camera_extrinsic.h"

#include <tf2_eigen/tf2_eigen.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_listener.h>

namespace semantic_edge_vo {

CameraExtrinsic::CameraExtrinsic(std::string base_frame, double lookup_timeout_seconds)
    : base_frame_(std::move(base_frame)),
      timeout_(lookup_timeout_seconds),
      buffer_(std::make_unique<tf2_ros::Buffer>()),
      listener_(std::make_unique<tf2_ros::TransformListener>(*buffer_)) {}

CameraExtrinsic::~CameraExtrinsic() = default;

Eigen::Isometry3d CameraExtrinsic::opticalDefault() {
  Eigen::Matrix3d rotation;
  rotation << 0, 0, 1, -1, 0, 0, 0, -1, 0;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = rotation;
  return pose;
}

Eigen::Isometry3d CameraExtrinsic::baseFromCamera(const std::string& camera_frame, bool* from_tf) {
  if (camera_frame != cached_frame_) {
    cached_frame_ = camera_frame;
    cached_ = opticalDefault();
    cached_from_tf_ = false;
  }
  if (!cached_from_tf_ && !camera_frame.empty() && camera_frame != base_frame_) {
    try {
      cached_ = tf2::transformToEigen(
          buffer_->lookupTransform(base_frame_, camera_frame, ros::Time(0), ros::Duration(timeout_)));
      cached_from_tf_ = true;
    } catch (const tf2::TransformException&) {
      // No extrinsic on tf (yet): keep the optical default.
    }
  }
  if (from_tf) *from_tf = cached_from_tf_;
  return cached_;
}

}  // namespace semantic_edge_vo
