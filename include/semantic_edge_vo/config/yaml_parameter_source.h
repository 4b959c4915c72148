#pragma once
#include <memory>
#include <string>

#include "semantic_edge_vo/config/parameter_source.h"

namespace semantic_edge_vo {

/// Parameters from one section of a YAML file laid out like config/semantic_edge_vo.yaml (one
/// block per nodelet): what the offline tools read with --config. yaml-cpp stays in the .cpp.
class YamlParameterSource : public ParameterSource {
 public:
  /// Parses `path`; an empty path gives an empty source (every get false: all defaults). Check
  /// error() for a file that is missing or not YAML.
  explicit YamlParameterSource(const std::string& path);
  ~YamlParameterSource() override;

  /// The block `name` ("edge_intake", "tracking", ...); empty (every get false) when absent.
  YamlParameterSource section(const std::string& name) const;

  bool get(const std::string& name, bool* value) const override;
  bool get(const std::string& name, int* value) const override;
  bool get(const std::string& name, double* value) const override;
  bool get(const std::string& name, std::string* value) const override;
  bool get(const std::string& name, std::vector<int>* value) const override;
  bool get(const std::string& name, std::vector<double>* value) const override;
  bool get(const std::string& name, std::vector<SemanticClass>* value) const override;
  std::string resolve(const std::string& name) const override;
  std::vector<std::string> names() const override;

  YamlParameterSource(const YamlParameterSource& other);

 private:
  struct Node;
  YamlParameterSource(std::string path, std::string prefix, std::unique_ptr<Node> node);
  template <typename T>
  bool read(const std::string& name, T* value) const;

  std::string path_, prefix_;
  std::unique_ptr<Node> node_;
};

}  // namespace semantic_edge_vo
