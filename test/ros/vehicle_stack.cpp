// rostest: the graph on a vehicle whose tf tree already has its frames. The camera's mounting comes
// from tf (base_link -> camera optical frame), and the path uses it; base_link already has a parent
// (chassis -> base_link), so odom -> base_link is never published (a warning says why) while
// nav_msgs/Odometry still is. With publish_tf false (vehicle_stack_no_tf.test) nothing at all goes
// on tf from the odometry, with or without a collision.
#include <mutex>
#include <set>

#include <gtest/gtest.h>
#include <nav_msgs/Odometry.h>
#include <ros/ros.h>
#include <rosgraph_msgs/Log.h>
#include <tf2_eigen/tf2_eigen.h>
#include <tf2_msgs/TFMessage.h>

#include "semantic_edge_vo/TrackedFrame.h"

namespace semantic_edge_vo {
namespace {

TEST(VehicleStack, MountingFromTfAndNoSecondParentOnTf) {
  ros::NodeHandle node;
  bool publish_tf = true;
  ASSERT_TRUE(ros::param::get("/tracking/publish_tf", publish_tf));
  std::mutex mutex;
  int odometry_count = 0;
  std::set<std::string> odometry_transforms;  // "parent -> child" published by the manager's nodelets
  std::vector<std::string> warnings;
  TrackedFrameConstPtr tracked;
  ros::Subscriber odometry_subscriber = node.subscribe<nav_msgs::Odometry>("/odometry", 100, [&](const nav_msgs::OdometryConstPtr&) {
    std::lock_guard<std::mutex> lock(mutex);
    ++odometry_count;
  });
  const auto on_tf = [&](const ros::MessageEvent<const tf2_msgs::TFMessage>& event) {
    if (event.getPublisherName() != "/semantic_edge_vo_manager") return;
    std::lock_guard<std::mutex> lock(mutex);
    for (const auto& transform : event.getMessage()->transforms)
      odometry_transforms.insert(transform.header.frame_id + " -> " + transform.child_frame_id);
  };
  ros::Subscriber tf_subscriber = node.subscribe<tf2_msgs::TFMessage>("/tf", 100, on_tf);
  ros::Subscriber tf_static_subscriber = node.subscribe<tf2_msgs::TFMessage>("/tf_static", 100, on_tf);
  ros::Subscriber tracked_subscriber = node.subscribe<TrackedFrame>("/tracked_frame", 10, [&](const TrackedFrameConstPtr& t) {
    std::lock_guard<std::mutex> lock(mutex);
    tracked = t;
  });
  ros::Subscriber log_subscriber = node.subscribe<rosgraph_msgs::Log>("/rosout", 100, [&](const rosgraph_msgs::LogConstPtr& log) {
    std::lock_guard<std::mutex> lock(mutex);
    if (log->level == rosgraph_msgs::Log::WARN) warnings.push_back(log->msg);
  });
  ros::AsyncSpinner spinner(2);
  spinner.start();
  const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(40.0);
  while (ros::WallTime::now() < deadline) {
    ros::WallDuration(0.2).sleep();
    std::lock_guard<std::mutex> lock(mutex);
    if (odometry_count >= 30) break;
  }
  std::lock_guard<std::mutex> lock(mutex);
  ASSERT_GE(odometry_count, 30) << "the odometry must run whatever tf holds";

  // The mounting the odometry used is the vehicle's (test launch file: 0.3 m ahead, 1.5 m up).
  ASSERT_TRUE(tracked);
  Eigen::Isometry3d T_base_cam;
  tf2::fromMsg(tracked->pose_base_camera, T_base_cam);
  EXPECT_LT((T_base_cam.translation() - Eigen::Vector3d(0.3, 0.0, 1.5)).norm(), 1e-6);
  EXPECT_LT((T_base_cam.linear().col(2) - Eigen::Vector3d::UnitX()).norm(), 1e-3) << "camera z must look along base_link x";

  // Nothing on tf that would give base_link (or the camera) a second parent; nothing at all without publish_tf.
  EXPECT_EQ(odometry_transforms.count("odom -> base_link"), 0u) << "base_link already has the parent chassis";
  EXPECT_EQ(odometry_transforms.count("base_link -> camera_optical_frame"), 0u) << "the mounting is on tf already";
  if (!publish_tf) {
    EXPECT_TRUE(odometry_transforms.empty()) << "publish_tf false: the odometry publishes nothing on tf";
    return;
  }
  bool warned = false;
  for (const std::string& warning : warnings) warned |= warning.find("already has the parent chassis") != std::string::npos;
  EXPECT_TRUE(warned) << "a warning must say why odom -> base_link is not published";
}

}  // namespace
}  // namespace semantic_edge_vo

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "vehicle_stack_test");
  return RUN_ALL_TESTS();
}
