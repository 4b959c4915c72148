#pragma once
#include <functional>
#include <map>
#include <mutex>
#include <string>

#include <ros/time.h>

namespace semantic_edge_vo {

/// Refused inputs: every refusal is counted and logged as a named error, throttled per reason so
/// that one bad stream does not hide another and does not flood the log. Thread-safe.
class InputRejections {
 public:
  /// @param[in] on_reject told each refusal's reason name (e.g. diagnostics counting drops)
  explicit InputRejections(std::string owner, std::function<void(const std::string&)> on_reject = nullptr,
                           double throttle_seconds = 5.0)
      : owner_(std::move(owner)), on_reject_(std::move(on_reject)), throttle_seconds_(throttle_seconds) {}

  /// Logs "<owner>: dropped <what>: <reason_name>: <detail>" at most once per throttle period per reason.
  void reject(const std::string& what, const std::string& reason_name, const std::string& detail);
  unsigned long total() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return total_;
  }

 private:
  struct Reason {
    ros::WallTime last_logged;
    unsigned long count = 0;
    unsigned long logged_at_count = 0;
  };
  std::string owner_;
  std::function<void(const std::string&)> on_reject_;
  double throttle_seconds_;
  mutable std::mutex mutex_;
  std::map<std::string, Reason> reasons_;
  unsigned long total_ = 0;
};

}  // namespace semantic_edge_vo
