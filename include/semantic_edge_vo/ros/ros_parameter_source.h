#pragma once
#include <ros/node_handle.h>

#include "semantic_edge_vo/config/parameter_loader.h"
#include "semantic_edge_vo/config/parameter_source.h"

namespace semantic_edge_vo {

/// Parameters of a node handle's namespace (a nodelet's private parameters).
class RosParameterSource : public ParameterSource {
 public:
  explicit RosParameterSource(const ros::NodeHandle& node) : node_(node) {}

  bool get(const std::string& name, bool* value) const override { return read(name, value); }
  bool get(const std::string& name, int* value) const override { return read(name, value); }
  bool get(const std::string& name, double* value) const override { return read(name, value); }
  bool get(const std::string& name, std::string* value) const override { return read(name, value); }
  bool get(const std::string& name, std::vector<int>* value) const override { return read(name, value); }
  bool get(const std::string& name, std::vector<double>* value) const override { return read(name, value); }
  bool get(const std::string& name, std::vector<SemanticClass>* value) const override;
  std::string resolve(const std::string& name) const override { return node_.resolveName(name); }
  std::vector<std::string> names() const override;

 private:
  template <typename T>
  bool read(const std::string& name, T* value) const {
    if (node_.getParam(name, *value)) return true;
    if (node_.hasParam(name)) reportError(resolve(name) + " has the wrong type");
    return false;
  }

  ros::NodeHandle node_;
};

/// Warns once, naming them, of the nodelet's private parameters that no option read: a typo would
/// otherwise silently run the default.
void warnUnknownParameters(const ParameterLoader& loader, const std::string& nodelet_name);

}  // namespace semantic_edge_vo
