#pragma once
#include <cstdint>
#include <vector>

#include "semantic_edge_vo/fields/nearest_neighbor_field.h"

namespace semantic_edge_vo {

/// A class mask with every class: any edge.
constexpr std::uint32_t kAllClasses = ~0u;

/// Is there an edge of a class a point has (any edge for ANNF/ONNF fields) within `radius` of a
/// pixel of a frame (full resolution)? The epipolar search asks this at every step along the line.
/// A per-pixel mask of the layers with a seed near the pixel answers most queries at once; only
/// where it says "maybe" is the field's exact lookup made, so the answers are the lookup's own.
class SharedClassEdgeTest {
 public:
  SharedClassEdgeTest(const NearestNeighborFieldView& field, double radius);

  bool operator()(std::uint32_t class_mask, float x, float y) const;
  /// Whether the class mask matters (a semantic field); otherwise every edge counts.
  bool classRestricted() const { return field_.kind == FieldKind::kSnnf; }

 private:
  const NearestNeighborFieldView& field_;
  float radius_;
  int width_ = 0, height_ = 0;
  std::vector<std::uint32_t> near_layers_;  ///< per pixel: layers with a seed whose pixel is within radius + 1 along each axis
};

}  // namespace semantic_edge_vo
