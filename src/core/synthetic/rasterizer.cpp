#include "semantic_edge_vo/synthetic/rasterizer.h"

#include <algorithm>
#include <cmath>

namespace semantic_edge_vo {
namespace synthetic {
namespace {

using Vertices = std::array<Eigen::Vector3d, ProjectedPolygon::kMaxEdges>;

/// Sutherland-Hodgman against z >= near. Returns the vertex count of the clipped polygon.
int clipNear(const Vertices& in, int count, double near, Vertices* out) {
  int n = 0;
  for (int i = 0; i < count; ++i) {
    const Eigen::Vector3d& a = in[static_cast<std::size_t>(i)];
    const Eigen::Vector3d& b = in[static_cast<std::size_t>((i + 1) % count)];
    const bool a_in = a.z() >= near, b_in = b.z() >= near;
    if (a_in) (*out)[static_cast<std::size_t>(n++)] = a;
    if (a_in != b_in && n < ProjectedPolygon::kMaxEdges) {
      const double t = (near - a.z()) / (b.z() - a.z());
      (*out)[static_cast<std::size_t>(n++)] = a + t * (b - a);
    }
  }
  return n;
}

}  // namespace

bool ProjectedPolygon::covers(double u, double v) const {
  for (int i = 0; i < edge_count; ++i) {
    const auto& e = edges[static_cast<std::size_t>(i)];
    if (e[0] * u + e[1] * v + e[2] < 0.0) return false;
  }
  return true;
}

namespace {

/// Where a polygon's image lies: rows y0..y1 and columns u_min..u_max (pixels).
struct ImageBounds {
  double u_min = 1e300, u_max = -1e300, v_min = 1e300, v_max = -1e300;
};

/// The polygon in the camera's image (clipped at `near`, its edges, inverse-depth plane and texture
/// frame in the camera frame). False when no part of it can be seen: behind, outside the frustum,
/// seen from behind (one-sided), edge-on or of no area.
bool projectPolygon(const Polygon& polygon, const Eigen::Isometry3d& T_cam_map, const PinholeCamera& camera, const Eigen::Vector3d planes[4],
                    double near, ProjectedPolygon* projected, ImageBounds* bounds) {
  const Eigen::Matrix3d R = T_cam_map.linear();
  const Eigen::Vector3d t = T_cam_map.translation();
  Vertices vertices, clipped;
  const int count = polygon.vertex_count;
  int behind = 0;
  std::array<int, 4> outside{};
  for (int i = 0; i < count; ++i) {
    const Eigen::Vector3d v = R * polygon.vertices[static_cast<std::size_t>(i)] + t;
    vertices[static_cast<std::size_t>(i)] = v;
    behind += v.z() < near;
    for (int p = 0; p < 4; ++p) outside[static_cast<std::size_t>(p)] += planes[p].dot(v) < 0.0;
  }
  if (behind == count || std::find(outside.begin(), outside.end(), count) != outside.end()) return false;
  const Eigen::Vector3d normal = R * polygon.normal;
  double distance = normal.dot(vertices[0]);  // plane: normal . X = distance
  if (!polygon.surface.two_sided && distance >= 0.0) return false;  // seen from behind
  if (std::abs(distance) < 1e-9) return false;                     // seen edge-on

  const int n = behind > 0 ? clipNear(vertices, count, near, &clipped) : count;
  const Vertices& poly = behind > 0 ? clipped : vertices;
  if (n < 3) return false;
  std::array<Eigen::Vector2d, ProjectedPolygon::kMaxEdges> pixels;
  double area = 0.0;
  for (int i = 0; i < n; ++i) pixels[static_cast<std::size_t>(i)] = camera.project(poly[static_cast<std::size_t>(i)]);
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector2d& a = pixels[static_cast<std::size_t>(i)];
    const Eigen::Vector2d& b = pixels[static_cast<std::size_t>((i + 1) % n)];
    area += a.x() * b.y() - b.x() * a.y();
  }
  if (std::abs(area) < 1e-12) return false;
  const double orientation = area > 0.0 ? 1.0 : -1.0;

  projected->polygon = &polygon;
  projected->edge_count = n;
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector2d& a = pixels[static_cast<std::size_t>(i)];
    const Eigen::Vector2d& b = pixels[static_cast<std::size_t>((i + 1) % n)];
    // Left of a->b is inside for counter-clockwise (positive area) polygons.
    projected->edges[static_cast<std::size_t>(i)] = {orientation * (a.y() - b.y()), orientation * (b.x() - a.x()),
                                                     orientation * (a.x() * b.y() - b.x() * a.y())};
    bounds->u_min = std::min(bounds->u_min, a.x());
    bounds->u_max = std::max(bounds->u_max, a.x());
    bounds->v_min = std::min(bounds->v_min, a.y());
    bounds->v_max = std::max(bounds->v_max, a.y());
  }
  // 1/z = (n . r) / distance with r = ((u - cx) / fx, (v - cy) / fy, 1).
  projected->inverse_depth = {normal.x() / (camera.fx * distance), normal.y() / (camera.fy * distance),
                              (normal.z() - normal.x() * camera.cx / camera.fx - normal.y() * camera.cy / camera.fy) / distance};
  projected->normal = distance < 0.0 ? normal : Eigen::Vector3d(-normal);  // towards the camera
  projected->tex_origin = R * polygon.tex_origin + t;
  projected->tex_u = R * polygon.tex_u;
  projected->tex_v = R * polygon.tex_v;
  return true;
}

/// Draws the projected polygon into the buffer where it is nearer than what is there (z-buffer on
/// inverse depth), row by row between its edges. True when any pixel shows it.
bool scanConvert(const ProjectedPolygon& projected, const ImageBounds& bounds, int id, VisibilityBuffer* buffer) {
  const int width = buffer->ids.cols, height = buffer->ids.rows;
  const int y0 = std::max(0, static_cast<int>(std::ceil(bounds.v_min))), y1 = std::min(height - 1, static_cast<int>(std::floor(bounds.v_max)));
  if (y0 > y1 || bounds.u_max < 0.0 || bounds.u_min > width - 1) return false;
  bool drawn = false;
  for (int y = y0; y <= y1; ++y) {
    double lo = std::max(0.0, bounds.u_min), hi = std::min(width - 1.0, bounds.u_max);
    for (int i = 0; i < projected.edge_count && lo <= hi; ++i) {
      const auto& e = projected.edges[static_cast<std::size_t>(i)];
      const double rest = e[1] * y + e[2];
      if (std::abs(e[0]) < 1e-12) {
        if (rest < 0.0) hi = -1.0;
      } else if (e[0] > 0.0) {
        lo = std::max(lo, -rest / e[0]);
      } else {
        hi = std::min(hi, -rest / e[0]);
      }
    }
    const int x0 = static_cast<int>(std::ceil(lo)), x1 = static_cast<int>(std::floor(hi));
    if (x0 > x1) continue;
    float* depth_row = buffer->inverse_depth.ptr<float>(y);
    int* id_row = buffer->ids.ptr<int>(y);
    const double row_base = projected.inverse_depth[1] * y + projected.inverse_depth[2];
    for (int x = x0; x <= x1; ++x) {
      const auto inverse_depth = static_cast<float>(projected.inverse_depth[0] * x + row_base);
      if (inverse_depth > depth_row[x]) {
        depth_row[x] = inverse_depth;
        id_row[x] = id;
        drawn = true;
      }
    }
  }
  return drawn;
}

}  // namespace

void rasterize(const std::vector<const Polygon*>& polygons, const Eigen::Isometry3d& T_map_cam,
               const PinholeCamera& camera, VisibilityBuffer* buffer, double near) {
  const int width = camera.width, height = camera.height;
  buffer->ids.create(height, width, CV_32SC1);
  buffer->ids.setTo(-1);
  buffer->inverse_depth.create(height, width, CV_32FC1);
  buffer->inverse_depth.setTo(0.0f);
  buffer->polygons.clear();

  const Eigen::Isometry3d T_cam_map = T_map_cam.inverse();
  // Side planes of the view frustum through the optical centre (n . X >= 0 inside), half a pixel out.
  const double left = -(camera.cx + 0.5) / camera.fx, right = (width - 0.5 - camera.cx) / camera.fx;
  const double top = -(camera.cy + 0.5) / camera.fy, bottom = (height - 0.5 - camera.cy) / camera.fy;
  const Eigen::Vector3d planes[4] = {{1.0, 0.0, -left}, {-1.0, 0.0, right}, {0.0, 1.0, -top}, {0.0, -1.0, bottom}};
  for (const Polygon* polygon : polygons) {
    ProjectedPolygon projected;
    ImageBounds bounds;
    if (!projectPolygon(*polygon, T_cam_map, camera, planes, near, &projected, &bounds)) continue;
    if (scanConvert(projected, bounds, static_cast<int>(buffer->polygons.size()), buffer)) buffer->polygons.push_back(projected);
  }
}

}  // namespace synthetic
}  // namespace semantic_edge_vo
