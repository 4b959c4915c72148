#include "semantic_edge_vo/ros/message_tracer.h"

#include "semantic_edge_vo/MessageTrace.h"

namespace semantic_edge_vo {

void MessageTracer::init(ros::NodeHandle& node, ParameterLoader* loader, const std::string& nodelet_name) {
  loader->load("trace_messages", &enabled_);
  nodelet_name_ = nodelet_name;
  if (enabled_) publisher_ = node.advertise<MessageTrace>("message_trace", 200);
}

void MessageTracer::report(const std::string& topic, const char* event, const void* message,
                           const ros::Time& stamp) const {
  MessageTrace trace;
  trace.header.stamp = stamp;
  trace.nodelet = nodelet_name_;
  trace.topic = topic;
  trace.event = event;
  trace.address = reinterpret_cast<std::uintptr_t>(message);
  publisher_.publish(trace);
}

}  // namespace semantic_edge_vo
