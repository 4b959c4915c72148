#pragma once
#include <string>

#include <ros/node_handle.h>
#include <ros/publisher.h>

#include "semantic_edge_vo/config/parameter_loader.h"

namespace semantic_edge_vo {

/// With the parameter `trace_messages` (default false), reports the address of every data message a
/// nodelet publishes or receives on `message_trace` (semantic_edge_vo/MessageTrace), so that zero-copy
/// passing inside one manager can be checked from outside. Costs nothing when disabled.
class MessageTracer {
 public:
  /// Reads `trace_messages` with the nodelet's other parameters.
  void init(ros::NodeHandle& node, ParameterLoader* loader, const std::string& nodelet_name);
  void published(const ros::Publisher& publisher, const void* message, const ros::Time& stamp) const {
    if (enabled_) report(publisher.getTopic(), "publish", message, stamp);
  }
  void received(const std::string& topic, const void* message, const ros::Time& stamp) const {
    if (enabled_) report(topic, "receive", message, stamp);
  }

 private:
  void report(const std::string& topic, const char* event, const void* message, const ros::Time& stamp) const;

  bool enabled_ = false;
  std::string nodelet_name_;
  ros::Publisher publisher_;
};

}  // namespace semantic_edge_vo
