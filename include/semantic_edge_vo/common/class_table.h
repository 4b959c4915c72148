#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace semantic_edge_vo {

/// Classes an edge pixel can belong to. Bit i of a class mask is entry i, so at most 32 classes.
struct SemanticClass {
  std::string name;
  int id = 0;                              ///< id in the source labelling (Cityscapes train id)
  std::array<std::uint8_t, 3> rgb{{0, 0, 0}};  ///< display colour
};

class ClassTable {
 public:
  static constexpr int kMaxClasses = 32;

  ClassTable() = default;
  explicit ClassTable(std::vector<SemanticClass> classes) : classes_(std::move(classes)) {}

  /// The 19 Cityscapes training classes with their official colours.
  static ClassTable cityscapes();
  /// One class, "edge": what the non-semantic Canny intake uses.
  static ClassTable singleEdgeClass();

  int size() const { return static_cast<int>(classes_.size()); }
  const SemanticClass& operator[](int i) const { return classes_[static_cast<std::size_t>(i)]; }
  const std::vector<SemanticClass>& classes() const { return classes_; }
  std::vector<std::string> names() const;
  /// Index of the class called `name`, or -1.
  int indexOf(const std::string& name) const;
  /// Empty when usable, otherwise what is wrong.
  std::string validate() const;

 private:
  std::vector<SemanticClass> classes_;
};

}  // namespace semantic_edge_vo
