#pragma once
#include <string>
#include <vector>

#include "semantic_edge_vo/common/class_table.h"

namespace semantic_edge_vo {

/// Where option values come from: the ROS parameter server (the nodelets) or a YAML file (the
/// offline tools), under the same names, so config/semantic_edge_vo.yaml configures both.
/// Names are relative ("canny/blur_sigma"). Each get returns false when the name is not set and
/// leaves the value alone; a value of the wrong type counts as not set and is reported by error().
class ParameterSource {
 public:
  virtual ~ParameterSource() = default;

  virtual bool get(const std::string& name, bool* value) const = 0;
  virtual bool get(const std::string& name, int* value) const = 0;
  virtual bool get(const std::string& name, double* value) const = 0;
  virtual bool get(const std::string& name, std::string* value) const = 0;
  virtual bool get(const std::string& name, std::vector<int>* value) const = 0;
  virtual bool get(const std::string& name, std::vector<double>* value) const = 0;
  /// A list of {name, id, rgb: [r, g, b]}.
  virtual bool get(const std::string& name, std::vector<SemanticClass>* value) const = 0;

  /// The full name for logs (the resolved ROS name, or file:section/name).
  virtual std::string resolve(const std::string& name) const = 0;
  /// Every name set in this source, relative ("canny/blur_sigma"; a list is one name), so that a
  /// name no option reads (a typo) can be reported.
  virtual std::vector<std::string> names() const = 0;
  /// Values that were set but unreadable, one per line; empty when all were fine.
  const std::string& error() const { return error_; }

 protected:
  void reportError(const std::string& message) const { error_ += (error_.empty() ? "" : "\n") + message; }

 private:
  mutable std::string error_;
};

}  // namespace semantic_edge_vo
