#include "semantic_edge_vo/ros/camera_extrinsic.h"

#include <iomanip>
#include <sstream>

#include <tf2_eigen/tf2_eigen.h>
#include <tf2_ros/buffer.h>

namespace semantic_edge_vo {

Eigen::Isometry3d opticalDefault() {
  Eigen::Matrix3d rotation;
  rotation << 0, 0, 1, -1, 0, 0, 0, -1, 0;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = rotation;
  return pose;
}

std::string opticalFrameDoubt(const Eigen::Matrix3d& R_base_cam) {
  const Eigen::Vector3d y = R_base_cam.col(1);
  if (y.z() < -0.5) return "";  // y down (within 60 degrees)
  std::ostringstream doubt;
  doubt << std::fixed << std::setprecision(2) << "its y axis points (" << y.x() << ", " << y.y() << ", " << y.z()
        << ") in base_link, not down: the images must carry the camera's optical frame (z forward, x right, y down; "
           "REP-103's *_optical_frame), not its body frame";
  return doubt.str();
}

CameraMounting resolveCameraMounting(const tf2_ros::Buffer& tf, const std::string& base_frame, const std::string& camera_frame,
                                     double wait) {
  CameraMounting mounting;
  if (camera_frame.empty() || camera_frame == base_frame) {
    mounting.T_base_cam = opticalDefault();
    mounting.assumption = "the images carry " + (camera_frame.empty() ? std::string("no frame_id") : "base_link's frame_id") +
                          ": assuming a forward-facing camera with its optical axes at " + base_frame + "'s origin";
    return mounting;
  }
  try {
    mounting.T_base_cam = tf2::transformToEigen(tf.lookupTransform(base_frame, camera_frame, ros::Time(0), ros::Duration(wait)));
    mounting.from_tf = true;
    const std::string doubt = opticalFrameDoubt(mounting.T_base_cam.linear());
    if (!doubt.empty()) mounting.assumption = "camera frame " + camera_frame + " does not look optical: " + doubt;
  } catch (const tf2::TransformException&) {
    std::ostringstream said;
    said << "no " << base_frame << " -> " << camera_frame << " transform on tf within " << wait << " s: assuming a forward-facing camera, " << camera_frame << " an optical frame (z forward, x right, y down) at "
         << base_frame << "'s origin (camera z = " << base_frame << " x). Publish the real extrinsic on tf (e.g. "
         << "static_transform_publisher) or raise tracking/extrinsic_wait";
    if (camera_frame.find("optical") == std::string::npos)
      said << "; note that " << camera_frame << " is not named like an optical frame";
    mounting.T_base_cam = opticalDefault();
    mounting.assumption = said.str();
  }
  return mounting;
}

std::string otherParentOnTf(const tf2_ros::Buffer& tf, const std::string& child, const std::string& parent) {
  std::string found;
  if (!tf._getParent(child, ros::Time(0), found) || found == parent) return "";
  return found;
}

}  // namespace semantic_edge_vo
