#pragma once
#include <boost/make_shared.hpp>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>

namespace semantic_edge_vo {

/// An empty message with only its stamp set: what the pairing tests look at.
template <typename Message>
boost::shared_ptr<const Message> stampedAt(double stamp) {
  auto message = boost::make_shared<Message>();
  message->header.stamp = ros::Time(stamp);
  return message;
}

inline sensor_msgs::ImageConstPtr imageAt(double stamp) { return stampedAt<sensor_msgs::Image>(stamp); }

}  // namespace semantic_edge_vo
