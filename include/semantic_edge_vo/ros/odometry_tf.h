#pragma once
#include <memory>
#include <set>
#include <string>

#include <tf2_ros/buffer.h>
#include <tf2_ros/static_transform_broadcaster.h>
#include <tf2_ros/transform_broadcaster.h>
#include <tf2_ros/transform_listener.h>

#include "semantic_edge_vo/config/live_options.h"
#include "semantic_edge_vo/ros/camera_extrinsic.h"

namespace semantic_edge_vo {

/// The Tracking nodelet's side of tf (docs/architecture.md, "Frames, the camera's mounting and tf"):
/// the camera's mounting, resolved once per odometry (from tf, or assumed and said once), and the
/// transforms it publishes, odom -> base_link and the assumed base_link -> camera, never over
/// another parent and not at all without publish_tf. Serial use only (the frame callback).
class OdometryTf {
 public:
  /// Call after ros is initialised (it listens to tf).
  explicit OdometryTf(TfOptions options);

  /// The camera frame of an image: the configured one, else the image's frame_id.
  std::string cameraFrameOf(const std::string& image_frame) const {
    return options_.camera_frame.empty() ? image_frame : options_.camera_frame;
  }
  /// Resolves the mounting of a new odometry: the first call waits up to extrinsic_wait for tf,
  /// later ones (restarts) do not.
  const CameraMounting& resolve(const std::string& camera_frame);
  const CameraMounting& mounting() const { return mounting_; }
  const std::string& cameraFrame() const { return camera_frame_; }

  /// odom -> base_link at `stamp` (and, the first time for a camera frame, the assumed mounting).
  void publish(const ros::Time& stamp, const Eigen::Isometry3d& T_odom_base);

 private:
  void publishAssumedMounting(const ros::Time& stamp);

  TfOptions options_;
  tf2_ros::Buffer buffer_;
  tf2_ros::TransformListener listener_{buffer_};
  tf2_ros::TransformBroadcaster broadcaster_;
  tf2_ros::StaticTransformBroadcaster static_broadcaster_;
  CameraMounting mounting_;
  std::string camera_frame_;  ///< the mounting's
  bool waited_ = false;
  std::string announced_camera_frame_;
  std::set<std::string> said_;  ///< assumptions warned about
};

}  // namespace semantic_edge_vo
