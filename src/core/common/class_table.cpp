#include "semantic_edge_vo/common/class_table.h"

#include <set>
#include <sstream>

namespace semantic_edge_vo {

ClassTable ClassTable::cityscapes() {
  return ClassTable({{"road", 0, {{128, 64, 128}}},       {"sidewalk", 1, {{244, 35, 232}}},
                     {"building", 2, {{70, 70, 70}}},       {"wall", 3, {{102, 102, 156}}},
                     {"fence", 4, {{190, 153, 153}}},       {"pole", 5, {{153, 153, 153}}},
                     {"traffic light", 6, {{250, 170, 30}}}, {"traffic sign", 7, {{220, 220, 0}}},
                     {"vegetation", 8, {{107, 142, 35}}},   {"terrain", 9, {{152, 251, 152}}},
                     {"sky", 10, {{70, 130, 180}}},         {"person", 11, {{220, 20, 60}}},
                     {"rider", 12, {{255, 0, 0}}},          {"car", 13, {{0, 0, 142}}},
                     {"truck", 14, {{0, 0, 70}}},           {"bus", 15, {{0, 60, 100}}},
                     {"train", 16, {{0, 80, 100}}},         {"motorcycle", 17, {{0, 0, 230}}},
                     {"bicycle", 18, {{119, 11, 32}}}});
}

ClassTable ClassTable::singleEdgeClass() { return ClassTable({{"edge", 0, {{255, 255, 255}}}}); }

std::vector<std::string> ClassTable::names() const {
  std::vector<std::string> names;
  names.reserve(classes_.size());
  for (const auto& c : classes_) names.push_back(c.name);
  return names;
}

int ClassTable::indexOf(const std::string& name) const {
  for (std::size_t i = 0; i < classes_.size(); ++i)
    if (classes_[i].name == name) return static_cast<int>(i);
  return -1;
}

std::string ClassTable::validate() const {
  std::ostringstream error;
  std::set<std::string> seen;
  if (classes_.empty()) {
    error << "class table is empty";
  } else if (size() > kMaxClasses) {
    error << "class table has " << size() << " classes, at most " << kMaxClasses << " fit a class mask";
  } else {
    for (const auto& c : classes_) {
      if (c.name.empty()) {
        error << "class with id " << c.id << " has no name";
        break;
      }
      if (!seen.insert(c.name).second) {
        error << "class name '" << c.name << "' appears twice";
        break;
      }
    }
  }
  return error.str();
}

}  // namespace semantic_edge_vo
