#include "semantic_edge_vo/common/edge_set.h"

namespace semantic_edge_vo {

void EdgeSet::reserve(std::size_t n) {
  u.reserve(n);
  v.reserve(n);
  normal_x.reserve(n);
  normal_y.reserve(n);
  strength.reserve(n);
  class_mask.reserve(n);
}

EdgeSetView EdgeSet::view() const { return {u, v, normal_x, normal_y, strength, class_mask}; }

bool EdgeSetView::consistent() const {
  const std::size_t n = u.size();
  return v.size() == n && normal_x.size() == n && normal_y.size() == n && strength.size() == n &&
         class_mask.size() == n;
}

}  // namespace semantic_edge_vo
