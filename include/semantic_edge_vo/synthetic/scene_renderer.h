#pragma once
#include <cstdint>
#include <vector>

#include <Eigen/Geometry>
#include <opencv2/core/mat.hpp>

#include "semantic_edge_vo/common/camera.h"
#include "semantic_edge_vo/synthetic/rasterizer.h"
#include "semantic_edge_vo/synthetic/road_profile.h"
#include "semantic_edge_vo/synthetic/scene_geometry.h"

namespace semantic_edge_vo {
namespace synthetic {

/// Lighting and the look of the sky.
struct LightingOptions {
  double sun_azimuth = 0.8;      ///< rad about the up axis of the map frame
  double sun_elevation = 0.7;    ///< rad above the horizon
  double ambient = 0.55;         ///< light on faces turned away from the sun
  double sun = 0.6;              ///< added at normal incidence
  double fog_distance = 700.0;   ///< haze reaches 63 % at this depth, m
  double cloud_cover = 0.5;      ///< 0: clear sky, 1: overcast
  bool antialiasing = true;      ///< 4 samples per pixel where the visible polygon changes

  std::string validate() const;
};

/// What the scene looks like from one pose, before the camera's own effects.
struct RenderedView {
  cv::Mat radiance;   ///< CV_32FC3, linear BGR in [0, ~1.2] (antialiased)
  cv::Mat depth;      ///< CV_32FC1, z along the optical axis, m; 0 on the sky (no surface)
  cv::Mat class_id;   ///< CV_8UC1, Cityscapes train id of the surface at the pixel centre (sky: 10)
  cv::Mat dynamic;    ///< CV_8UC1, 255 on moving objects
};

/// Renders polygons with procedural materials. Depth and class are exact at the pixel centre.
class SceneRenderer {
 public:
  SceneRenderer(const PinholeCamera& camera, const RoadProfile& road, const LightingOptions& lighting);

  void render(const std::vector<const Polygon*>& polygons, const Eigen::Isometry3d& T_map_cam, RenderedView* view);

 private:
  Eigen::Vector3f shade(const ProjectedPolygon& polygon, float light, double u, double v, double* depth) const;
  Eigen::Vector3f sky(const Eigen::Isometry3d& T_map_cam, double u, double v) const;
  /// True when polygons a and b of the visibility buffer meet without a visible seam (strips of one
  /// surface): no antialiasing needed between them.
  bool seamless(int a, int b, const std::vector<float>& light) const;
  void antialias(const Eigen::Isometry3d& T_map_cam, const std::vector<float>& light, RenderedView* view) const;

  PinholeCamera camera_;
  RoadProfile road_;
  LightingOptions lighting_;
  Eigen::Vector3d to_sun_;
  VisibilityBuffer buffer_;
};

}  // namespace synthetic
}  // namespace semantic_edge_vo
