#include "semantic_edge_vo/ros/nodelet_diagnostics.h"

#include <algorithm>
#include <iomanip>
#include <sstream>

#include <diagnostic_msgs/DiagnosticArray.h>

namespace semantic_edge_vo {
namespace {

std::string fixed(double value, int decimals) {
  std::ostringstream text;
  text << std::fixed << std::setprecision(decimals) << value;
  return text.str();
}

diagnostic_msgs::KeyValue keyValue(const std::string& key, const std::string& value) {
  diagnostic_msgs::KeyValue pair;
  pair.key = key;
  pair.value = value;
  return pair;
}

}  // namespace

void DiagnosticCounts::input(std::uint32_t seq) {
  ++inputs_;
  // A step back, or a jump of thousands, is a new publisher (or a bag played again), not a loss.
  if (seq != 0 && last_seq_ != 0 && seq > last_seq_ && seq - last_seq_ < 10000) lost_total_ += seq - last_seq_ - 1;
  if (seq != 0) last_seq_ = seq;
}

diagnostic_msgs::DiagnosticStatus DiagnosticCounts::takePeriod(double seconds) {
  diagnostic_msgs::DiagnosticStatus status;
  status.level = diagnostic_msgs::DiagnosticStatus::OK;
  status.values.push_back(keyValue("input rate (Hz)", fixed(seconds > 0.0 ? inputs_ / seconds : 0.0, 1)));
  if (!times_ms_.empty()) {
    std::sort(times_ms_.begin(), times_ms_.end());
    status.values.push_back(keyValue("processing time median (ms)", fixed(times_ms_[times_ms_.size() / 2], 1)));
    status.values.push_back(keyValue("processing time max (ms)", fixed(times_ms_.back(), 1)));
  }
  status.values.push_back(keyValue("inputs dropped (period)", std::to_string(dropped_period_)));
  status.values.push_back(keyValue("inputs dropped (total)", std::to_string(dropped_total_)));
  status.values.push_back(keyValue("inputs lost in queues (total)", std::to_string(lost_total_)));
  if (dropped_period_ > 0) {
    status.level = diagnostic_msgs::DiagnosticStatus::WARN;
    status.message = std::to_string(dropped_period_) + " inputs dropped";
  }
  inputs_ = 0;
  dropped_period_ = 0;
  times_ms_.clear();
  return status;
}

NodeletDiagnostics::NodeletDiagnostics(ros::NodeHandle node, std::string name, double period)
    : name_(std::move(name)), period_(period) {
  publisher_ = node.advertise<diagnostic_msgs::DiagnosticArray>("/diagnostics", 10);
  timer_ = node.createWallTimer(ros::WallDuration(period_), &NodeletDiagnostics::onTimer, this);
}

void NodeletDiagnostics::input(std::uint32_t seq) {
  std::lock_guard<std::mutex> lock(mutex_);
  counts_.input(seq);
}
void NodeletDiagnostics::processed(double ms) {
  std::lock_guard<std::mutex> lock(mutex_);
  counts_.processed(ms);
}
void NodeletDiagnostics::dropped(unsigned long count) {
  std::lock_guard<std::mutex> lock(mutex_);
  counts_.dropped(count);
}
void NodeletDiagnostics::set(const std::string& key, const std::string& value) {
  std::lock_guard<std::mutex> lock(mutex_);
  values_[key] = value;
}
void NodeletDiagnostics::problem(const std::string& name, Level level, const std::string& message) {
  std::lock_guard<std::mutex> lock(mutex_);
  problems_[name] = {level, message};
}
void NodeletDiagnostics::clear(const std::string& name) {
  std::lock_guard<std::mutex> lock(mutex_);
  problems_.erase(name);
}

diagnostic_msgs::DiagnosticStatus NodeletDiagnostics::takeStatus() {
  if (check_) check_();
  std::lock_guard<std::mutex> lock(mutex_);
  diagnostic_msgs::DiagnosticStatus status = counts_.takePeriod(period_);
  status.name = name_;
  status.hardware_id = "semantic_edge_vo";
  for (const auto& [key, value] : values_) status.values.push_back(keyValue(key, value));
  for (const auto& [problem_name, problem] : problems_) {
    if (problem.level < status.level) continue;
    if (problem.level > status.level) status.message.clear();
    status.level = problem.level;
    status.message += (status.message.empty() ? "" : "; ") + problem.message;
  }
  if (status.message.empty()) status.message = "ok";
  return status;
}

void NodeletDiagnostics::onTimer(const ros::WallTimerEvent&) {
  diagnostic_msgs::DiagnosticArray array;
  array.header.stamp = ros::Time::now();
  array.status.push_back(takeStatus());
  publisher_.publish(array);
}

}  // namespace semantic_edge_vo
