#pragma once
#include <cstdint>
#include <functional>
#include <map>
#include <mutex>
#include <string>
#include <vector>

#include <diagnostic_msgs/DiagnosticStatus.h>
#include <ros/node_handle.h>
#include <ros/wall_timer.h>

namespace semantic_edge_vo {

/// What a nodelet saw during one diagnostics period, and since it started. ROS-free arithmetic for
/// NodeletDiagnostics (tested without a master).
class DiagnosticCounts {
 public:
  /// One input arrived. `seq`: its header's sequence number when its publisher numbers them
  /// consecutively (roscpp does for messages it serialises, rosbag play too; the nodelets number
  /// theirs), so a gap is inputs lost in a queue on the way; 0: not numbered.
  void input(std::uint32_t seq = 0);
  void processed(double ms) { times_ms_.push_back(ms); }
  void dropped(unsigned long count = 1) {
    dropped_period_ += count;
    dropped_total_ += count;
  }

  /// The period's figures as key-values, and the level (OK, or WARN when inputs were dropped);
  /// starts a new period.
  diagnostic_msgs::DiagnosticStatus takePeriod(double seconds);

 private:
  unsigned long inputs_ = 0, dropped_period_ = 0, dropped_total_ = 0, lost_total_ = 0;
  std::vector<double> times_ms_;
  std::uint32_t last_seq_ = 0;
};

/// A nodelet's health on /diagnostics (diagnostic_msgs/DiagnosticArray, one status per period),
/// as diagnostic_updater publishes it (Debian 12 does not package diagnostic_updater): input rate,
/// processing time, queue depth, inputs dropped or lost, the nodelet's own values, and named
/// problems that raise the level until cleared. Thread-safe.
class NodeletDiagnostics {
 public:
  using Level = std::uint8_t;  ///< diagnostic_msgs::DiagnosticStatus::OK, WARN, ERROR

  /// @param[in] name the status's name (the nodelet's)
  NodeletDiagnostics(ros::NodeHandle node, std::string name, double period = 1.0);

  void input(std::uint32_t seq = 0);
  void processed(double ms);
  void dropped(unsigned long count = 1);
  void set(const std::string& key, const std::string& value);
  /// A named problem: the status takes its level and message until clear(name).
  void problem(const std::string& name, Level level, const std::string& message);
  void clear(const std::string& name);
  /// Runs before each publication (e.g. a watchdog that sets or clears problems).
  void beforePublishing(std::function<void()> check) { check_ = std::move(check); }
  /// The status of the period that ends now (what each publication carries).
  diagnostic_msgs::DiagnosticStatus takeStatus();

 private:
  void onTimer(const ros::WallTimerEvent&);

  std::string name_;
  double period_;
  ros::Publisher publisher_;
  ros::WallTimer timer_;
  std::function<void()> check_;
  std::mutex mutex_;  // guards what follows
  DiagnosticCounts counts_;
  std::map<std::string, std::string> values_;
  struct Problem {
    Level level;
    std::string message;
  };
  std::map<std::string, Problem> problems_;
};

}  // namespace semantic_edge_vo
