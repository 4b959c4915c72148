#pragma once
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "semantic_edge_vo/config/parameter_source.h"

namespace semantic_edge_vo {

/// Reads parameters into option structs that already hold the defaults, and remembers every value
/// (given or default) so the caller can print them all once at start-up, every name it read (so
/// the source's other names can be reported as unknown) and every given value that is not the default.
class ParameterLoader {
 public:
  explicit ParameterLoader(const ParameterSource& source) : source_(source) {}

  /// Reads `name` into `value` when set; otherwise keeps the default.
  template <typename T>
  void load(const std::string& name, T* value, const char* unit = "") {
    const std::string default_value = text(*value);
    const bool given = source_.get(name, value);
    record(name, *value, default_value, unit, given);
  }
  /// Same for float options (sources store doubles).
  void load(const std::string& name, float* value, const char* unit = "") {
    const std::string default_value = text(*value);
    double wide = *value;
    const bool given = source_.get(name, &wide);
    *value = static_cast<float>(wide);
    record(name, *value, default_value, unit, given);
  }

  /// The source's names that no load() read, resolved and comma-separated; empty when none.
  std::string unknownNames() const;
  /// "name = value (default d)" for every given value that differs from its default.
  const std::vector<std::string>& changedFromDefaults() const { return changed_; }

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
  static std::string text(const T& value) {
    std::ostringstream out;
    print(out, value);
    return out.str();
  }

  template <typename T>
  void record(const std::string& name, const T& value, const std::string& default_value, const char* unit, bool given) {
    const std::string value_text = text(value);
    summary_ << "\n  " << source_.resolve(name) << " = " << value_text << (*unit ? " " : "") << unit << (given ? "" : " (default)");
    read_.insert(name);
    if (given && value_text != default_value) changed_.push_back(name + " = " + value_text + " (default " + default_value + ")");
  }

  const ParameterSource& source_;
  std::ostringstream summary_;
  std::set<std::string> read_;
  std::vector<std::string> changed_;
};

}  // namespace semantic_edge_vo
