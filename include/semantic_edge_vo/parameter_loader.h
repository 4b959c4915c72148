#pragma once
#include <sstream>
#include <string>
#include <vector>

#include "semantic_edge_vo/parameter_source.h"

namespace semantic_edge_vo {

/// Reads parameters into option structs that already hold the defaults, and remembers every value
/// (given or default) so the caller can print them all once at start-up.
class ParameterLoader {
 public:
  explicit ParameterLoader(const ParameterSource& source) : source_(source) {}

  /// Reads `name` into `value` when set; otherwise keeps the default.
  template <typename T>
  void load(const std::string& name, T* value, const char* unit = "") {
    const bool given = source_.get(name, value);
    record(name, *value, unit, given);
  }
  /// Same for float options (sources store doubles).
  void load(const std::string& name, float* value, const char* unit = "") {
    double wide = *value;
    const bool given = source_.get(name, &wide);
    *value = static_cast<float>(wide);
    record(name, *value, unit, given);
  }

  const ParameterSource& source() const { return source_; }
  /// "name = value unit (default)" lines for the start-up log.
  std::string summary() const { return summary_.str(); }

 private:
  template <typename T>
  static void print(std::ostream& out, const T& value) {
    out << value;
  }
  template <typename T>
  static void print(std::ostream& out, const std::vector<T>& values) {
    out << '[';
    for (std::size_t i = 0; i < values.size(); ++i) out << (i ? ", " : "") << values[i];
    out << ']';
  }
  static void print(std::ostream& out, const std::vector<SemanticClass>& classes) { out << classes.size() << " classes"; }

  template <typename T>
  void record(const std::string& name, const T& value, const char* unit, bool given) {
    summary_ << "\n  " << source_.resolve(name) << " = ";
    print(summary_, value);
    summary_ << (*unit ? " " : "") << unit << (given ? "" : " (default)");
  }

  const ParameterSource& source_;
  std::ostringstream summary_;
};

}  // namespace semantic_edge_vo
