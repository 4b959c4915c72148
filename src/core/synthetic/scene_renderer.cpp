#include "semantic_edge_vo/synthetic/scene_renderer.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "semantic_edge_vo/synthetic/materials.h"
#include "semantic_edge_vo/synthetic/noise.h"

namespace semantic_edge_vo {
namespace synthetic {
namespace {

constexpr std::uint8_t kSkyClass = 10;
const Eigen::Vector3f kHorizon(0.80f, 0.83f, 0.87f);  // RGB
const Eigen::Vector3f kZenith(0.33f, 0.50f, 0.78f);

cv::Vec3f toBgr(const Eigen::Vector3f& rgb) { return {rgb.z(), rgb.y(), rgb.x()}; }

}  // namespace

std::string LightingOptions::validate() const {
  std::ostringstream error;
  if (!(ambient >= 0.0 && sun >= 0.0)) error << "ambient and sun must be >= 0 (got " << ambient << ", " << sun << ")";
  else if (!(fog_distance > 0.0)) error << "fog_distance must be > 0 m (got " << fog_distance << ")";
  else if (!(cloud_cover >= 0.0 && cloud_cover <= 1.0)) error << "cloud_cover must be in [0, 1] (got " << cloud_cover << ")";
  return error.str();
}

SceneRenderer::SceneRenderer(const PinholeCamera& camera, const RoadProfile& road, const LightingOptions& lighting)
    : camera_(camera), road_(road), lighting_(lighting) {
  to_sun_ = Eigen::Vector3d(std::cos(lighting.sun_elevation) * std::sin(lighting.sun_azimuth),
                            -std::sin(lighting.sun_elevation),
                            std::cos(lighting.sun_elevation) * std::cos(lighting.sun_azimuth));
}

Eigen::Vector3f SceneRenderer::shade(const ProjectedPolygon& projected, float light, double u, double v,
                                     double* depth) const {
  const double z = 1.0 / projected.inverseDepthAt(u, v);
  *depth = z;
  const Eigen::Vector3d ray((u - camera_.cx) / camera_.fx, (v - camera_.cy) / camera_.fy, 1.0);
  const Eigen::Vector3d offset = z * ray - projected.tex_origin;
  // Surface moved by one pixel step in u and in v: footprints of the pixel along a and b.
  const Eigen::Vector3d step_u = z * Eigen::Vector3d(1.0 / camera_.fx, 0.0, 0.0) - z * z * projected.inverse_depth[0] * ray;
  const Eigen::Vector3d step_v = z * Eigen::Vector3d(0.0, 1.0 / camera_.fy, 0.0) - z * z * projected.inverse_depth[1] * ray;
  const Polygon& polygon = *projected.polygon;
  ShadingPoint point;
  point.a = offset.dot(projected.tex_u);
  point.b = offset.dot(projected.tex_v);
  point.footprint_a = std::abs(step_u.dot(projected.tex_u)) + std::abs(step_v.dot(projected.tex_u));
  point.footprint_b = std::abs(step_u.dot(projected.tex_v)) + std::abs(step_v.dot(projected.tex_v));
  point.footprint = std::sqrt(point.footprint_a * point.footprint_b);
  point.extent_a = polygon.extent_a;
  point.extent_b = polygon.extent_b;
  point.variant = polygon.surface.variant;
  const Eigen::Vector3f reflected = albedo(polygon.surface.material, point, road_) * light;
  const float haze = 1.0f - std::exp(static_cast<float>(-z / lighting_.fog_distance));
  return reflected + (kHorizon - reflected) * haze;
}

Eigen::Vector3f SceneRenderer::sky(const Eigen::Isometry3d& T_map_cam, double u, double v) const {
  const Eigen::Vector3d direction =
      (T_map_cam.linear() * Eigen::Vector3d((u - camera_.cx) / camera_.fx, (v - camera_.cy) / camera_.fy, 1.0)).normalized();
  const double elevation = -direction.y();
  const auto t = static_cast<float>(std::clamp(elevation / 0.45, 0.0, 1.0));
  Eigen::Vector3f colour = kHorizon + (kZenith - kHorizon) * std::sqrt(t);
  if (elevation > 0.01 && lighting_.cloud_cover > 0.0) {
    // Clouds on a plane 1 km up: they drift past slowly as the camera moves, like real ones.
    const double distance = 1000.0 / elevation;
    const Eigen::Vector3d at = T_map_cam.translation() + distance * direction;
    const double footprint = distance / (camera_.fx * elevation);
    const float density = fractalNoise(at.x(), at.z(), 1500.0, 4, footprint, 77);
    const float cover = std::clamp((density - 0.75f + 0.5f * static_cast<float>(lighting_.cloud_cover)) * 4.0f, 0.0f, 1.0f);
    colour += (Eigen::Vector3f(0.93f, 0.93f, 0.95f) - colour) * cover * std::min(1.0f, 5.0f * t);
  }
  return colour;
}

void SceneRenderer::render(const std::vector<const Polygon*>& polygons, const Eigen::Isometry3d& T_map_cam,
                           RenderedView* view) {
  rasterize(polygons, T_map_cam, camera_, &buffer_);
  const int width = camera_.width, height = camera_.height;
  view->radiance.create(height, width, CV_32FC3);
  view->depth.create(height, width, CV_32FC1);
  view->class_id.create(height, width, CV_8UC1);
  view->dynamic.create(height, width, CV_8UC1);

  // Light per polygon: ambient, sun on faces turned to it, and a little skylight on upward faces.
  std::vector<float> light(buffer_.polygons.size());
  for (std::size_t i = 0; i < light.size(); ++i) {
    const Eigen::Vector3d normal = T_map_cam.linear() * buffer_.polygons[i].normal;
    light[i] = static_cast<float>(lighting_.ambient + lighting_.sun * std::max(0.0, normal.dot(to_sun_)) +
                                  0.15 * std::max(0.0, -normal.y()));
  }
  for (int y = 0; y < height; ++y) {
    const int* ids = buffer_.ids.ptr<int>(y);
    auto* radiance = view->radiance.ptr<cv::Vec3f>(y);
    auto* depth = view->depth.ptr<float>(y);
    auto* class_id = view->class_id.ptr<std::uint8_t>(y);
    auto* dynamic = view->dynamic.ptr<std::uint8_t>(y);
    for (int x = 0; x < width; ++x) {
      const int id = ids[x];
      if (id < 0) {
        radiance[x] = toBgr(sky(T_map_cam, x, y));
        depth[x] = 0.0f;
        class_id[x] = kSkyClass;
        dynamic[x] = 0;
        continue;
      }
      const ProjectedPolygon& projected = buffer_.polygons[static_cast<std::size_t>(id)];
      double z = 0.0;
      radiance[x] = toBgr(shade(projected, light[static_cast<std::size_t>(id)], x, y, &z));
      depth[x] = static_cast<float>(z);
      class_id[x] = projected.polygon->surface.class_id;
      dynamic[x] = projected.polygon->dynamic ? 255 : 0;
    }
  }
  if (lighting_.antialiasing) antialias(T_map_cam, light, view);
}

bool SceneRenderer::seamless(int a, int b, const std::vector<float>& light) const {
  if (a < 0 || b < 0) return false;
  const Polygon& pa = *buffer_.polygons[static_cast<std::size_t>(a)].polygon;
  const Polygon& pb = *buffer_.polygons[static_cast<std::size_t>(b)].polygon;
  return pa.surface.material == pb.surface.material && pa.surface.variant == pb.surface.variant &&
         light[static_cast<std::size_t>(a)] == light[static_cast<std::size_t>(b)] &&
         std::abs(buffer_.polygons[static_cast<std::size_t>(a)].inverse_depth[2] -
                  buffer_.polygons[static_cast<std::size_t>(b)].inverse_depth[2]) <
             0.05 * std::abs(buffer_.polygons[static_cast<std::size_t>(a)].inverse_depth[2]);
}

void SceneRenderer::antialias(const Eigen::Isometry3d& T_map_cam, const std::vector<float>& light,
                              RenderedView* view) const {
  // Rotated-grid sub-samples.
  static const double kOffsets[4][2] = {{-0.125, -0.375}, {0.375, -0.125}, {0.125, 0.375}, {-0.375, 0.125}};
  const int width = camera_.width, height = camera_.height;
  const cv::Mat& ids = buffer_.ids;
  // Pixels next to a visible seam (right or lower neighbour on another surface), both sides.
  cv::Mat seam = cv::Mat::zeros(height, width, CV_8UC1);
  for (int y = 0; y < height; ++y) {
    const int* row = ids.ptr<int>(y);
    const int* below = ids.ptr<int>(std::min(y + 1, height - 1));
    std::uint8_t* mark = seam.ptr<std::uint8_t>(y);
    std::uint8_t* mark_below = seam.ptr<std::uint8_t>(std::min(y + 1, height - 1));
    for (int x = 0; x < width; ++x) {
      if (x + 1 < width && row[x + 1] != row[x] && !seamless(row[x], row[x + 1], light)) mark[x] = mark[x + 1] = 1;
      if (below[x] != row[x] && !seamless(row[x], below[x], light)) mark[x] = mark_below[x] = 1;
    }
  }
  for (int y = 0; y < height; ++y) {
    const std::uint8_t* mark = seam.ptr<std::uint8_t>(y);
    for (int x = 0; x < width; ++x) {
      if (!mark[x]) continue;
      // Candidates: the polygons seen at the 3x3 neighbourhood's centres.
      int candidates[9];
      int count = 0;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const int other = ids.at<int>(std::clamp(y + dy, 0, height - 1), std::clamp(x + dx, 0, width - 1));
          if (other >= 0 && std::find(candidates, candidates + count, other) == candidates + count) candidates[count++] = other;
        }
      Eigen::Vector3f sum = Eigen::Vector3f::Zero();
      for (const auto& offset : kOffsets) {
        const double u = x + offset[0], v = y + offset[1];
        int best = -1;
        double best_inverse_depth = 0.0;
        for (int c = 0; c < count; ++c) {
          const ProjectedPolygon& projected = buffer_.polygons[static_cast<std::size_t>(candidates[c])];
          const double inverse_depth = projected.inverseDepthAt(u, v);
          if (inverse_depth > best_inverse_depth && projected.covers(u, v)) {
            best = candidates[c];
            best_inverse_depth = inverse_depth;
          }
        }
        double z = 0.0;
        sum += best < 0 ? sky(T_map_cam, u, v)
                        : shade(buffer_.polygons[static_cast<std::size_t>(best)], light[static_cast<std::size_t>(best)], u, v, &z);
      }
      view->radiance.at<cv::Vec3f>(y, x) = toBgr(0.25f * sum);
    }
  }
}

}  // namespace synthetic
}  // namespace semantic_edge_vo
