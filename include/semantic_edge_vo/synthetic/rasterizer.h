#pragma once
#include <array>
#include <vector>

#include <Eigen/Geometry>
#include <opencv2/core/mat.hpp>

#include "semantic_edge_vo/common/camera.h"
#include "semantic_edge_vo/synthetic/scene_geometry.h"

namespace semantic_edge_vo {
namespace synthetic {

/// A polygon as one frame sees it. Inside the (near-clipped) polygon every edge function
/// e0 u + e1 v + e2 is >= 0, and the inverse depth is exactly affine in the pixel coordinates:
/// 1 / z = i0 u + i1 v + i2, so depth is the exact ray-plane intersection, not an interpolation.
struct ProjectedPolygon {
  static constexpr int kMaxEdges = Polygon::kMaxVertices + 1;  // near clipping adds one
  const Polygon* polygon = nullptr;
  std::array<double, 3> inverse_depth{};
  std::array<std::array<double, 3>, kMaxEdges> edges{};
  int edge_count = 0;
  // The surface in the camera frame, for shading.
  Eigen::Vector3d normal, tex_origin, tex_u, tex_v;

  double inverseDepthAt(double u, double v) const { return inverse_depth[0] * u + inverse_depth[1] * v + inverse_depth[2]; }
  bool covers(double u, double v) const;
};

/// Which polygon each pixel centre sees, and its inverse depth (0 and id -1: nothing, the sky).
struct VisibilityBuffer {
  cv::Mat ids;            ///< CV_32SC1, index into `polygons` or -1
  cv::Mat inverse_depth;  ///< CV_32FC1, 1/m (for the depth test; exact depth comes from the plane)
  std::vector<ProjectedPolygon> polygons;
};

/// Z-buffered scan conversion of convex planar polygons at pixel centres. Back faces of one-sided
/// polygons, polygons outside the view and parts nearer than `near` are left out.
void rasterize(const std::vector<const Polygon*>& polygons, const Eigen::Isometry3d& T_map_cam,
               const PinholeCamera& camera, VisibilityBuffer* buffer, double near = 0.1);

}  // namespace synthetic
}  // namespace semantic_edge_vo
