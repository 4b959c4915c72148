#pragma once
#include <cstdint>

#include <Eigen/Core>

namespace semantic_edge_vo {

/// A point hosted by a keyframe, parameterised by its inverse depth there (paper III-A).
struct MapPoint {
  float u = 0, v = 0;                   ///< full-resolution pixel in the host keyframe
  double inverse_depth = 0.0;           ///< 1 / z in the host's optical frame, 1/m (arbitrary monocular scale)
  double inverse_depth_variance = 1.0;  ///< 1/m^2
  std::uint32_t class_mask = 0;         ///< class bits; 0: supportive point (photometric residual only)
  /// Layers of a semantic field (SNNF) its edge is matched in: its classes, or the all-edges layer
  /// where the drive cannot rely on them (ClassReliability). Other field kinds do not read it.
  std::uint32_t field_layers = 0;
  Eigen::Vector2f normal = Eigen::Vector2f::Zero();  ///< unit image-gradient direction (edge points)
  int observations = 0;                 ///< depth measurements fused so far

  bool isEdge() const { return class_mask != 0; }
  /// Used by tracking and mapping only once its depth was measured (a propagated prior is not enough)
  /// to within 30 % (one sigma).
  bool hasDepth() const {
    return observations > 0 && inverse_depth > 0.0 && inverse_depth_variance < 0.09 * inverse_depth * inverse_depth;
  }
};

}  // namespace semantic_edge_vo
