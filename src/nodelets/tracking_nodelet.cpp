// Tracking: SemanticEdgeFrame + NearestNeighborField (paired by stamp) + KeyframeMap -> pose of
// every frame on tf (odom -> base_link), nav_msgs/Odometry, TrackingStatus, TrackedFrame.
//
// Foundation stage: the frame-to-keyframe alignment is not in yet, so the camera is held at its
// start pose and the status says INITIALIZING. Frames, stamps, pairing and outputs are final.
#include <message_filters/subscriber.h>
#include <message_filters/time_synchronizer.h>
#include <nav_msgs/Odometry.h>
#include <nodelet/nodelet.h>
#include <pluginlib/class_list_macros.hpp>
#include <tf2_eigen/tf2_eigen.h>
#include <tf2_ros/static_transform_broadcaster.h>
#include <tf2_ros/transform_broadcaster.h>

#include "semantic_edge_vo/KeyframeMap.h"
#include "semantic_edge_vo/NearestNeighborField.h"
#include "semantic_edge_vo/SemanticEdgeFrame.h"
#include "semantic_edge_vo/TrackedFrame.h"
#include "semantic_edge_vo/TrackingStatus.h"
#include "semantic_edge_vo/ros/camera_extrinsic.h"
#include "semantic_edge_vo/ros/conversions.h"
#include "semantic_edge_vo/ros/input_rejections.h"
#include "semantic_edge_vo/ros/message_tracer.h"
#include "semantic_edge_vo/ros/parameter_loader.h"

namespace semantic_edge_vo {

class TrackingNodelet : public nodelet::Nodelet {
 private:
  using Sync = message_filters::TimeSynchronizer<SemanticEdgeFrame, NearestNeighborField>;

  void onInit() override {
    ros::NodeHandle& node = getNodeHandle();
    ParameterLoader loader(getPrivateNodeHandle());
    loader.load("odom_frame", &odom_frame_);
    loader.load("base_frame", &base_frame_);
    loader.load("publish_tf", &publish_tf_);
    loader.load("publish_default_camera_tf", &publish_default_camera_tf_);
    NODELET_INFO_STREAM("parameters:" << loader.summary());
    if (odom_frame_.empty() || base_frame_.empty() || odom_frame_ == base_frame_) {
      NODELET_ERROR_STREAM("invalid parameters, the nodelet stays inert: odom_frame and base_frame must be "
                           "non-empty and differ (got '" << odom_frame_ << "', '" << base_frame_ << "')");
      return;
    }
    rejections_ = std::make_unique<InputRejections>(getName());
    extrinsic_ = std::make_unique<CameraExtrinsic>(base_frame_, 0.0);
    tracer_.init(node, getPrivateNodeHandle(), getName());
    odometry_publisher_ = node.advertise<nav_msgs::Odometry>("odometry", 10);
    status_publisher_ = node.advertise<TrackingStatus>("tracking_status", 10);
    tracked_publisher_ = node.advertise<TrackedFrame>("tracked_frame", 10);
    frame_subscriber_.subscribe(node, "edge_frame", 5);
    field_subscriber_.subscribe(node, "nn_field", 5);
    sync_ = std::make_unique<Sync>(frame_subscriber_, field_subscriber_, 10);
    sync_->registerCallback(&TrackingNodelet::onFrame, this);
    map_subscriber_ = node.subscribe("keyframe_map", 2, &TrackingNodelet::onKeyframeMap, this);
  }

  void onKeyframeMap(const KeyframeMapConstPtr& map) {
    tracer_.received(map_subscriber_.getTopic(), map.get(), map->header.stamp);
    std::lock_guard<std::mutex> lock(map_mutex_);
    keyframe_map_ = map;
  }

  void onFrame(const SemanticEdgeFrameConstPtr& frame, const NearestNeighborFieldConstPtr& field) {
    tracer_.received(frame_subscriber_.getTopic(), frame.get(), frame->header.stamp);
    tracer_.received(field_subscriber_.getTopic(), field.get(), field->header.stamp);
    const ros::WallTime start = ros::WallTime::now();
    std::string error;
    const NearestNeighborFieldView fields = fieldView(*field, &error);
    if (error.empty()) error = fields.validate();
    if (!error.empty()) {
      rejections_->reject("frame", "invalid_field", error);
      return;
    }
    std::uint32_t keyframe_id = 0;
    {
      std::lock_guard<std::mutex> lock(map_mutex_);
      if (keyframe_map_ && !keyframe_map_->keyframes.empty()) keyframe_id = keyframe_map_->keyframes.back().id;
    }
    const std::string& camera_frame = frame->header.frame_id;
    bool extrinsic_from_tf = false;
    const Eigen::Isometry3d T_base_cam = extrinsic_->baseFromCamera(camera_frame, &extrinsic_from_tf);
    if (!extrinsic_from_tf && publish_default_camera_tf_ && camera_frame != announced_camera_frame_) {
      publishDefaultCameraTf(camera_frame, frame->header.stamp, T_base_cam);
    }
    const Eigen::Isometry3d T_odom_base = baseInOdom(T_world_cam_, T_base_cam);
    const ros::Time stamp = frame->header.stamp;

    if (publish_tf_) {
      geometry_msgs::TransformStamped transform = tf2::eigenToTransform(T_odom_base);
      transform.header.stamp = stamp;
      transform.header.frame_id = odom_frame_;
      transform.child_frame_id = base_frame_;
      tf_broadcaster_.sendTransform(transform);
    }
    auto odometry = boost::make_shared<nav_msgs::Odometry>();
    odometry->header.stamp = stamp;
    odometry->header.frame_id = odom_frame_;
    odometry->child_frame_id = base_frame_;
    odometry->pose.pose = toPoseMsg(T_odom_base);
    // Monocular: position is up to an unknown scale; the covariance says we do not know it.
    for (int i = 0; i < 6; ++i) odometry->pose.covariance[static_cast<std::size_t>(i * 7)] = i < 3 ? 1e3 : 1e-2;
    odometry_publisher_.publish(nav_msgs::OdometryConstPtr(odometry));

    auto tracked = boost::make_shared<TrackedFrame>();
    tracked->header.stamp = stamp;
    tracked->header.frame_id = "world";
    tracked->pose_world_camera = toPoseMsg(T_world_cam_);
    tracked->pose_trusted = true;
    tracked->keyframe_id = keyframe_id;
    tracked_publisher_.publish(TrackedFrameConstPtr(tracked));
    tracer_.published(tracked_publisher_, tracked.get(), stamp);

    auto status = boost::make_shared<TrackingStatus>();
    status->header = frame->header;
    status->state = TrackingStatus::INITIALIZING;
    status->pose_published = publish_tf_;
    status->keyframe_id = keyframe_id;
    status->num_points = static_cast<std::uint32_t>(frame->sampled_edges.size() + frame->support_u.size());
    status->num_edge_points = static_cast<std::uint32_t>(frame->sampled_edges.size());
    status->time_ms = static_cast<float>((ros::WallTime::now() - start).toSec() * 1e3);
    status->scale_is_arbitrary = true;
    status_publisher_.publish(TrackingStatusConstPtr(status));
  }

  /// Without a base_link -> camera transform on tf, announce the default one so rviz can show the camera.
  void publishDefaultCameraTf(const std::string& camera_frame, const ros::Time& stamp, const Eigen::Isometry3d& T_base_cam) {
    geometry_msgs::TransformStamped transform = tf2::eigenToTransform(T_base_cam);
    transform.header.stamp = stamp;
    transform.header.frame_id = base_frame_;
    transform.child_frame_id = camera_frame;
    static_broadcaster_.sendTransform(transform);
    announced_camera_frame_ = camera_frame;
    NODELET_INFO_STREAM("no " << base_frame_ << " -> " << camera_frame
                              << " transform on tf: publishing the optical-rotation default as a static transform");
  }

  std::string odom_frame_ = "odom";
  std::string base_frame_ = "base_link";
  bool publish_tf_ = true;
  bool publish_default_camera_tf_ = true;

  std::unique_ptr<InputRejections> rejections_;
  std::unique_ptr<CameraExtrinsic> extrinsic_;
  MessageTracer tracer_;
  message_filters::Subscriber<SemanticEdgeFrame> frame_subscriber_;
  message_filters::Subscriber<NearestNeighborField> field_subscriber_;
  std::unique_ptr<Sync> sync_;
  ros::Subscriber map_subscriber_;
  ros::Publisher odometry_publisher_, status_publisher_, tracked_publisher_;
  tf2_ros::TransformBroadcaster tf_broadcaster_;
  tf2_ros::StaticTransformBroadcaster static_broadcaster_;
  std::string announced_camera_frame_;

  Eigen::Isometry3d T_world_cam_ = Eigen::Isometry3d::Identity();  // frame callback only
  std::mutex map_mutex_;                                           // guards keyframe_map_
  KeyframeMapConstPtr keyframe_map_;
};

}  // namespace semantic_edge_vo

PLUGINLIB_EXPORT_CLASS(semantic_edge_vo::TrackingNodelet, nodelet::Nodelet)
