#pragma once
#include <sstream>
#include <string>

#include <ros/node_handle.h>

namespace semantic_edge_vo {

/// Reads parameters into option structs that already hold the defaults, and remembers every value
/// (given or default) so the nodelet can print them all once at start-up.
class ParameterLoader {
 public:
  explicit ParameterLoader(const ros::NodeHandle& node) : node_(node) {}

  /// Reads `name` into `value` when set; otherwise keeps the default.
  template <typename T>
  void load(const std::string& name, T* value, const char* unit = "") {
    const bool given = node_.getParam(name, *value);
    record(name, *value, unit, given);
  }
  /// Same for float options (the parameter server stores doubles).
  void load(const std::string& name, float* value, const char* unit = "") {
    double wide = *value;
    const bool given = node_.getParam(name, wide);
    *value = static_cast<float>(wide);
    record(name, *value, unit, given);
  }

  /// "name = value unit (default)" lines for the start-up log.
  std::string summary() const { return summary_.str(); }

 private:
  template <typename T>
  void record(const std::string& name, const T& value, const char* unit, bool given) {
    summary_ << "\n  " << node_.resolveName(name) << " = " << value << (*unit ? " " : "") << unit
             << (given ? "" : " (default)");
  }

  ros::NodeHandle node_;
  std::ostringstream summary_;
};

}  // namespace semantic_edge_vo
