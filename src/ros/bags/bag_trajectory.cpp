#include "semantic_edge_vo/ros/bags/bag_trajectory.h"

#include <set>
#include <sstream>

#include <nav_msgs/Odometry.h>
#include <rosbag/bag.h>
#include <rosbag/view.h>

#include "semantic_edge_vo/ros/conversions.h"

namespace semantic_edge_vo {
namespace {

/// "a, b" of the bag's topics that carry nav_msgs/Odometry, for error messages.
std::string odometryTopics(const rosbag::Bag& bag) {
  rosbag::View view(bag, rosbag::TypeQuery("nav_msgs/Odometry"));
  std::set<std::string> topics;
  for (const rosbag::ConnectionInfo* connection : view.getConnections()) topics.insert(connection->topic);
  std::string list;
  for (const std::string& topic : topics) list += (list.empty() ? "" : ", ") + topic;
  return list.empty() ? "none" : list;
}

}  // namespace

std::string readOdometryBag(const std::string& path, const std::string& topic, const Eigen::Isometry3d& T_base_cam,
                            Trajectory* trajectory) {
  try {
    rosbag::Bag bag(path, rosbag::bagmode::Read);
    rosbag::View view(bag, rosbag::TopicQuery(topic));
    Trajectory result;
    const Eigen::Isometry3d T_cam_base = T_base_cam.inverse();
    std::size_t index = 0;
    for (const rosbag::MessageInstance& message : view) {
      const nav_msgs::Odometry::ConstPtr odometry = message.instantiate<nav_msgs::Odometry>();
      if (!odometry)
        return path + ": topic " + topic + " carries " + message.getDataType() + ", not nav_msgs/Odometry";
      const double stamp = odometry->header.stamp.toSec();
      if (!result.stamps.empty() && stamp <= result.stamps.back()) {
        std::ostringstream error;
        error.precision(15);
        error << path << ": message " << index << " on " << topic << " has stamp " << stamp
              << " s, not after the previous one (" << result.stamps.back() << " s)";
        return error.str();
      }
      result.stamps.push_back(stamp);
      result.poses.push_back(T_cam_base * fromPoseMsg(odometry->pose.pose) * T_base_cam);
      ++index;
    }
    if (result.poses.empty())
      return path + ": no message on " + topic + " (topics with nav_msgs/Odometry: " + odometryTopics(bag) + ")";
    *trajectory = std::move(result);
    return "";
  } catch (const rosbag::BagException& exception) {
    return path + ": " + exception.what();
  }
}

}  // namespace semantic_edge_vo
