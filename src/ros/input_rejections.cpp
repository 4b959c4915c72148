#include "semantic_edge_vo/ros/input_rejections.h"

#include <ros/console.h>

namespace semantic_edge_vo {

void InputRejections::reject(const std::string& what, const std::string& reason_name, const std::string& detail) {
  if (on_reject_) on_reject_(reason_name);
  std::lock_guard<std::mutex> lock(mutex_);
  ++total_;
  Reason& reason = reasons_[reason_name];
  ++reason.count;
  const ros::WallTime now = ros::WallTime::now();
  if (reason.logged_at_count != 0 && (now - reason.last_logged).toSec() < throttle_seconds_) return;
  const unsigned long suppressed = reason.count - reason.logged_at_count - 1;
  ROS_ERROR_STREAM(owner_ << ": dropped " << what << ": " << reason_name << ": " << detail
                          << (suppressed ? " (" + std::to_string(suppressed) + " more since the last report)" : ""));
  reason.last_logged = now;
  reason.logged_at_count = reason.count;
}

}  // namespace semantic_edge_vo
