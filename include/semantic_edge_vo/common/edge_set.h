#pragma once
#include <cstdint>
#include <vector>

#include "semantic_edge_vo/common/array_view.h"

namespace semantic_edge_vo {

struct EdgeSetView;

/// Index of the pixel nearest to a coordinate > -0.5 (halves round up, like std::lround, but inline:
/// no libm call per edge). Callers clamp or skip smaller coordinates first.
inline int nearestPixelIndex(float coordinate) { return static_cast<int>(coordinate + 0.5f); }

/// Thinned edge pixels of one image, structure of arrays (the layout of SemanticEdgeFrame).
/// Positions in full-resolution pixels; normals are unit image-gradient directions (dark to bright).
struct EdgeSet {
  std::vector<float> u, v;
  std::vector<float> normal_x, normal_y;
  std::vector<float> strength;             ///< edge probability in [0, 1]
  std::vector<std::uint32_t> class_mask;   ///< bit i: class i of the class table

  std::size_t size() const { return u.size(); }
  void reserve(std::size_t n);
  /// Inline: detectors call it once per edge pixel.
  void push_back(float pu, float pv, float nx, float ny, float s, std::uint32_t mask) {
    u.push_back(pu);
    v.push_back(pv);
    normal_x.push_back(nx);
    normal_y.push_back(ny);
    strength.push_back(s);
    class_mask.push_back(mask);
  }
  EdgeSetView view() const;
};

/// The same arrays, owned elsewhere (an EdgeSet or a message).
struct EdgeSetView {
  ArrayView<float> u, v;
  ArrayView<float> normal_x, normal_y;
  ArrayView<float> strength;
  ArrayView<std::uint32_t> class_mask;

  std::size_t size() const { return u.size(); }
  /// True when every array has the same length.
  bool consistent() const;
};

}  // namespace semantic_edge_vo
