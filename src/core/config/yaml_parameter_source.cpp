#include "semantic_edge_vo/config/yaml_parameter_source.h"

#include <sstream>

#include <yaml-cpp/yaml.h>

namespace semantic_edge_vo {

struct YamlParameterSource::Node {
  YAML::Node root;
};

YamlParameterSource::YamlParameterSource(const std::string& path) : path_(path), node_(std::make_unique<Node>()) {
  if (path.empty()) return;
  try {
    node_->root = YAML::LoadFile(path);
  } catch (const YAML::Exception& e) {
    reportError(path + ": " + e.what());
  }
}

YamlParameterSource::YamlParameterSource(std::string path, std::string prefix, std::unique_ptr<Node> node)
    : path_(std::move(path)), prefix_(std::move(prefix)), node_(std::move(node)) {}

YamlParameterSource::YamlParameterSource(const YamlParameterSource& other)
    : ParameterSource(other), path_(other.path_), prefix_(other.prefix_), node_(std::make_unique<Node>(*other.node_)) {}

YamlParameterSource::~YamlParameterSource() = default;

namespace {

/// The node at "a/b/c" below `root`, undefined when any part is missing. Rebinds with reset():
/// YAML::Node::operator= would assign into the tree.
YAML::Node lookUp(const YAML::Node& root, const std::string& name) {
  YAML::Node node = root;
  std::istringstream parts(name);
  std::string part;
  while (std::getline(parts, part, '/')) {
    if (!node.IsMap()) return YAML::Node(YAML::NodeType::Undefined);
    const YAML::Node& map = node;
    const YAML::Node next = map[part];  // const lookup: never inserts
    if (!next.IsDefined()) return YAML::Node(YAML::NodeType::Undefined);
    node.reset(next);
  }
  return node;
}

/// Appends the names of the values below `node` (a map's keys joined by '/'; a list is one value).
void collectNames(const YAML::Node& node, const std::string& prefix, std::vector<std::string>* names) {
  if (!node.IsMap()) {
    if (!prefix.empty()) names->push_back(prefix);
    return;
  }
  for (const auto& entry : node) collectNames(entry.second, prefix + (prefix.empty() ? "" : "/") + entry.first.as<std::string>(), names);
}

}  // namespace

std::vector<std::string> YamlParameterSource::names() const {
  std::vector<std::string> names;
  collectNames(node_->root, "", &names);
  return names;
}

YamlParameterSource YamlParameterSource::section(const std::string& name) const {
  auto node = std::make_unique<Node>();
  node->root = lookUp(node_->root, name);
  return YamlParameterSource(path_, prefix_ + name + "/", std::move(node));
}

template <typename T>
bool YamlParameterSource::read(const std::string& name, T* value) const {
  const YAML::Node node = lookUp(node_->root, name);
  if (!node.IsDefined() || node.IsNull()) return false;
  try {
    *value = node.as<T>();
    return true;
  } catch (const YAML::Exception&) {
    reportError(resolve(name) + " has the wrong type");
    return false;
  }
}

bool YamlParameterSource::get(const std::string& name, bool* value) const { return read(name, value); }
bool YamlParameterSource::get(const std::string& name, int* value) const { return read(name, value); }
bool YamlParameterSource::get(const std::string& name, double* value) const { return read(name, value); }
bool YamlParameterSource::get(const std::string& name, std::string* value) const { return read(name, value); }
bool YamlParameterSource::get(const std::string& name, std::vector<int>* value) const { return read(name, value); }
bool YamlParameterSource::get(const std::string& name, std::vector<double>* value) const { return read(name, value); }

bool YamlParameterSource::get(const std::string& name, std::vector<SemanticClass>* value) const {
  const YAML::Node list = lookUp(node_->root, name);
  if (!list.IsDefined() || list.IsNull()) return false;
  std::vector<SemanticClass> classes;
  for (std::size_t i = 0; list.IsSequence() && i < list.size(); ++i) {
    const YAML::Node entry = list[i];
    try {
      SemanticClass c;
      c.name = entry["name"].as<std::string>();
      c.id = entry["id"].as<int>();
      const auto rgb = entry["rgb"].as<std::vector<int>>();
      if (rgb.size() != 3) throw YAML::Exception(YAML::Mark::null_mark(), "rgb");
      for (int k = 0; k < 3; ++k) c.rgb[static_cast<std::size_t>(k)] = static_cast<std::uint8_t>(rgb[static_cast<std::size_t>(k)]);
      classes.push_back(c);
    } catch (const YAML::Exception&) {
      reportError(resolve(name) + "[" + std::to_string(i) + "] must be {name: string, id: int, rgb: [r, g, b]}");
      return false;
    }
  }
  if (!list.IsSequence()) {
    reportError(resolve(name) + " must be a list of {name, id, rgb}");
    return false;
  }
  *value = std::move(classes);
  return true;
}

std::string YamlParameterSource::resolve(const std::string& name) const {
  return (path_.empty() ? "" : path_ + ":") + prefix_ + name;
}

}  // namespace semantic_edge_vo
