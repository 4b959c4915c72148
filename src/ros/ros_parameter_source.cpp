#include "semantic_edge_vo/ros/ros_parameter_source.h"

#include <ros/console.h>
#include <xmlrpcpp/XmlRpcValue.h>

namespace semantic_edge_vo {

std::vector<std::string> RosParameterSource::names() const {
  std::vector<std::string> all, names;
  if (!node_.getParamNames(all)) return names;
  const std::string prefix = node_.getNamespace() + "/";
  for (const std::string& name : all) {
    if (name.compare(0, prefix.size(), prefix) != 0) continue;
    const std::string own = name.substr(prefix.size());
    if (own.compare(0, 5, "live/") != 0) names.push_back(own);  // dynamic_reconfigure's (LiveParameters)
  }
  return names;
}

bool RosParameterSource::get(const std::string& name, std::vector<SemanticClass>* value) const {
  XmlRpc::XmlRpcValue list;
  if (!node_.getParam(name, list)) return false;
  if (list.getType() != XmlRpc::XmlRpcValue::TypeArray) {
    reportError(resolve(name) + " must be a list of {name, id, rgb}");
    return false;
  }
  std::vector<SemanticClass> classes;
  for (int i = 0; i < list.size(); ++i) {
    XmlRpc::XmlRpcValue& entry = list[i];
    const bool usable = entry.getType() == XmlRpc::XmlRpcValue::TypeStruct && entry.hasMember("name") &&
                        entry["name"].getType() == XmlRpc::XmlRpcValue::TypeString && entry.hasMember("id") &&
                        entry["id"].getType() == XmlRpc::XmlRpcValue::TypeInt && entry.hasMember("rgb") &&
                        entry["rgb"].getType() == XmlRpc::XmlRpcValue::TypeArray && entry["rgb"].size() == 3;
    if (!usable) {
      reportError(resolve(name) + "[" + std::to_string(i) + "] must be {name: string, id: int, rgb: [r, g, b]}");
      return false;
    }
    SemanticClass c;
    c.name = static_cast<std::string>(entry["name"]);
    c.id = static_cast<int>(entry["id"]);
    for (int k = 0; k < 3; ++k) {
      if (entry["rgb"][k].getType() != XmlRpc::XmlRpcValue::TypeInt) {
        reportError(resolve(name) + "[" + std::to_string(i) + "].rgb must hold integers");
        return false;
      }
      c.rgb[static_cast<std::size_t>(k)] = static_cast<std::uint8_t>(static_cast<int>(entry["rgb"][k]));
    }
    classes.push_back(c);
  }
  *value = std::move(classes);
  return true;
}

void warnUnknownParameters(const ParameterLoader& loader, const std::string& nodelet_name) {
  const std::string unknown = loader.unknownNames();
  if (!unknown.empty()) ROS_WARN_STREAM(nodelet_name << ": unknown parameters, ignored (no option has these names): " << unknown);
}

}  // namespace semantic_edge_vo
