#include "semantic_edge_vo/ros/odometry_tf.h"

#include <ros/console.h>
#include <tf2_eigen/tf2_eigen.h>

namespace semantic_edge_vo {

OdometryTf::OdometryTf(TfOptions options) : options_(std::move(options)) {}

const CameraMounting& OdometryTf::resolve(const std::string& camera_frame) {
  const double wait = waited_ ? 0.0 : options_.extrinsic_wait;
  waited_ = true;
  mounting_ = resolveCameraMounting(buffer_, options_.frames.base_frame, camera_frame, wait);
  camera_frame_ = camera_frame;
  if (!mounting_.assumption.empty() && said_.insert(mounting_.assumption).second)
    ROS_WARN_STREAM("tracking: " << mounting_.assumption);
  else if (mounting_.from_tf)
    ROS_INFO_STREAM("tracking: camera extrinsic from tf: " << options_.frames.base_frame << " -> " << camera_frame);
  return mounting_;
}

void OdometryTf::publish(const ros::Time& stamp, const Eigen::Isometry3d& T_odom_base) {
  if (!options_.publish_tf) return;
  if (!mounting_.from_tf && options_.publish_default_camera_tf && camera_frame_ != announced_camera_frame_)
    publishAssumedMounting(stamp);
  const FrameNames& frames = options_.frames;
  const std::string other = otherParentOnTf(buffer_, frames.base_frame, frames.odom_frame);
  if (!other.empty()) {
    ROS_WARN_STREAM_THROTTLE(10.0, "tracking: not publishing " << frames.odom_frame << " -> " << frames.base_frame << ": "
                                                               << frames.base_frame << " already has the parent " << other
                                                               << " on tf (set base_frame to the root of the vehicle's tree, "
                                                                  "or publish_tf:=false); odometry is still published");
    return;
  }
  geometry_msgs::TransformStamped transform = tf2::eigenToTransform(T_odom_base);
  transform.header.stamp = stamp;
  transform.header.frame_id = frames.odom_frame;
  transform.child_frame_id = frames.base_frame;
  broadcaster_.sendTransform(transform);
}

void OdometryTf::publishAssumedMounting(const ros::Time& stamp) {
  announced_camera_frame_ = camera_frame_;
  const std::string& base = options_.frames.base_frame;
  const std::string other = otherParentOnTf(buffer_, camera_frame_, base);
  if (!other.empty()) {
    ROS_WARN_STREAM("tracking: not publishing the assumed " << base << " -> " << camera_frame_ << ": " << camera_frame_
                                                            << " already has the parent " << other << " on tf");
    return;
  }
  geometry_msgs::TransformStamped transform = tf2::eigenToTransform(mounting_.T_base_cam);
  transform.header.stamp = stamp;
  transform.header.frame_id = base;
  transform.child_frame_id = camera_frame_;
  static_broadcaster_.sendTransform(transform);
  ROS_INFO_STREAM("tracking: publishing the assumed " << base << " -> " << camera_frame_ << " as a static transform");
}

}  // namespace semantic_edge_vo
