#pragma once
#include <cstdint>

#include <Eigen/Core>

#include "semantic_edge_vo/synthetic/road_profile.h"
#include "semantic_edge_vo/synthetic/scene_geometry.h"

namespace semantic_edge_vo {
namespace synthetic {

/// Where a material is evaluated: surface coordinates and the size of a pixel on the surface.
struct ShadingPoint {
  double a = 0.0;           ///< texture coordinate along tex_u, m
  double b = 0.0;           ///< texture coordinate along tex_v, m
  double footprint_a = 0.0; ///< metres of a per pixel (pattern finer than this fades out)
  double footprint_b = 0.0; ///< metres of b per pixel
  double footprint = 0.0;   ///< their geometric mean, for isotropic noise
  float extent_a = 0.0f;    ///< face size along a, m
  float extent_b = 0.0f;    ///< face size along b, m
  std::uint32_t variant = 0;
};

/// Reflectance (linear RGB in [0, 1]) of a procedural material: bricks, windows, asphalt with lane
/// markings, foliage... evaluated in surface coordinates, so it sticks to the surface from frame to
/// frame, and box-filtered over the pixel footprint, so it does not alias in the distance.
Eigen::Vector3f albedo(Material material, const ShadingPoint& point, const RoadProfile& road);

}  // namespace synthetic
}  // namespace semantic_edge_vo
