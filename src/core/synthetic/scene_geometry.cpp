#include "semantic_edge_vo/synthetic/scene_geometry.h"

#include <algorithm>
#include <cmath>

#include "semantic_edge_vo/synthetic/random.h"

namespace semantic_edge_vo {
namespace synthetic {

void Polygon::transform(const Eigen::Isometry3d& T) {
  for (int i = 0; i < vertex_count; ++i) vertices[static_cast<std::size_t>(i)] = T * vertices[static_cast<std::size_t>(i)];
  normal = T.linear() * normal;
  tex_origin = T * tex_origin;
  tex_u = T.linear() * tex_u;
  tex_v = T.linear() * tex_v;
}

void addPolygon(Polygons* out, std::initializer_list<Eigen::Vector3d> vertices, const Eigen::Vector3d& outward,
                const Surface& surface, const Eigen::Vector3d& tex_origin, const Eigen::Vector3d& tex_u,
                const Eigen::Vector3d& tex_v, float extent_a, float extent_b) {
  addPolygon(out, vertices.begin(), static_cast<int>(vertices.size()), outward, surface, tex_origin, tex_u, tex_v,
             extent_a, extent_b);
}

void addPolygon(Polygons* out, const Eigen::Vector3d* vertices, int count, const Eigen::Vector3d& outward,
                const Surface& surface, const Eigen::Vector3d& tex_origin, const Eigen::Vector3d& tex_u,
                const Eigen::Vector3d& tex_v, float extent_a, float extent_b) {
  if (count < 3 || count > Polygon::kMaxVertices) return;
  Polygon polygon;
  for (int i = 0; i < count; ++i) polygon.vertices[static_cast<std::size_t>(polygon.vertex_count++)] = vertices[i];
  const Eigen::Vector3d& v0 = polygon.vertices[0];
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  for (int i = 1; i + 1 < polygon.vertex_count; ++i)  // robust to a degenerate first triangle
    normal += (polygon.vertices[static_cast<std::size_t>(i)] - v0).cross(polygon.vertices[static_cast<std::size_t>(i + 1)] - v0);
  if (normal.norm() < 1e-12) return;  // degenerate (zero area)
  normal.normalize();
  polygon.normal = normal.dot(outward) < 0.0 ? -normal : normal;
  polygon.tex_origin = tex_origin;
  polygon.tex_u = tex_u;
  polygon.tex_v = tex_v;
  polygon.extent_a = extent_a;
  polygon.extent_b = extent_b;
  polygon.surface = surface;
  out->push_back(polygon);
}

void addBox(Polygons* out, const Eigen::Isometry3d& pose, const Eigen::Vector3d& size, const BoxSurfaces& surfaces) {
  const double hx = 0.5 * size.x(), h = size.y(), hz = 0.5 * size.z();
  const Eigen::Vector3d normals[4] = {Eigen::Vector3d::UnitX(), -Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitZ(),
                                      -Eigen::Vector3d::UnitZ()};
  const double half_depth[4] = {hx, hx, hz, hz}, half_width[4] = {hz, hz, hx, hx};
  const Eigen::Vector3d rise = h * up();
  for (int i = 0; i < 4; ++i) {
    const Eigen::Vector3d n = pose.linear() * normals[i];
    const Eigen::Vector3d along = n.cross(Eigen::Vector3d::UnitY());  // left to right seen from outside
    const Eigen::Vector3d centre = pose * (half_depth[i] * normals[i]);
    const Eigen::Vector3d left = centre - half_width[i] * along, right = centre + half_width[i] * along;
    addPolygon(out, {left, right, right + rise, left + rise}, n, surfaces.faces[static_cast<std::size_t>(i)], left,
               along, up(), static_cast<float>(2.0 * half_width[i]), static_cast<float>(h));
  }
  const Eigen::Vector3d corner = pose * Eigen::Vector3d(-hx, -h, -hz);
  const Eigen::Vector3d ex = pose.linear() * Eigen::Vector3d::UnitX(), ez = pose.linear() * Eigen::Vector3d::UnitZ();
  addPolygon(out, {corner, corner + size.x() * ex, corner + size.x() * ex + size.z() * ez, corner + size.z() * ez}, up(),
             surfaces.faces[4], corner, ex, ez, static_cast<float>(size.x()), static_cast<float>(size.z()));
}

void addGableRoof(Polygons* out, const Eigen::Isometry3d& pose, double width, double length, double eaves,
                  double ridge, const Surface& roof, const Surface& gable) {
  const double hx = 0.5 * width, hz = 0.5 * length;
  auto p = [&](double x, double height, double z) { return Eigen::Vector3d(pose * Eigen::Vector3d(x, -height, z)); };
  const Eigen::Vector3d ez = pose.linear() * Eigen::Vector3d::UnitZ();
  for (double side : {-1.0, 1.0}) {
    const Eigen::Vector3d eave_a = p(side * hx, eaves, -hz), ridge_a = p(0.0, ridge, -hz);
    const Eigen::Vector3d slope = (ridge_a - eave_a).normalized();
    const Eigen::Vector3d outward = pose.linear() * Eigen::Vector3d(side, -1.0, 0.0);
    addPolygon(out, {eave_a, p(side * hx, eaves, hz), p(0.0, ridge, hz), ridge_a}, outward, roof, eave_a, ez, slope,
               static_cast<float>(length), static_cast<float>((ridge_a - eave_a).norm()));
  }
  for (double end : {-1.0, 1.0}) {
    const Eigen::Vector3d outward = pose.linear() * Eigen::Vector3d(0.0, 0.0, end);
    const Eigen::Vector3d left = p(-hx, eaves, end * hz);
    addPolygon(out, {left, p(hx, eaves, end * hz), p(0.0, ridge, end * hz)}, outward, gable, p(-hx, 0.0, end * hz),
               pose.linear() * Eigen::Vector3d::UnitX(), up(), static_cast<float>(width), static_cast<float>(ridge));
  }
}

void addLathe(Polygons* out, const Eigen::Isometry3d& pose, const std::vector<Ring>& rings, int sides,
              const Surface& surface, double jitter, std::uint64_t jitter_seed) {
  constexpr double kTwoPi = 6.283185307179586;
  sides = std::clamp(sides, 3, Polygon::kMaxVertices);
  Random random(jitter_seed);
  // Vertex ring by ring, in the object frame.
  std::vector<std::vector<Eigen::Vector3d>> grid(rings.size());
  for (std::size_t r = 0; r < rings.size(); ++r)
    for (int k = 0; k < sides; ++k) {
      const double angle = kTwoPi * k / sides;
      const double radius = rings[r].radius * (1.0 + (jitter > 0.0 ? jitter * (2.0 * random.uniform() - 1.0) : 0.0));
      grid[r].push_back(pose * Eigen::Vector3d(radius * std::cos(angle), -rings[r].height, radius * std::sin(angle)));
    }
  const Eigen::Vector3d axis_up = pose.linear() * up();
  const Eigen::Vector3d base = pose.translation();
  const double side_length = kTwoPi * std::max(rings[0].radius, 0.05) / sides;
  for (std::size_t r = 0; r + 1 < rings.size(); ++r) {
    for (int k = 0; k < sides; ++k) {
      const auto k1 = static_cast<std::size_t>((k + 1) % sides), k0 = static_cast<std::size_t>(k);
      const Eigen::Vector3d &a = grid[r][k0], &b = grid[r][k1], &c = grid[r + 1][k1], &d = grid[r + 1][k0];
      const Eigen::Vector3d centre = 0.25 * (a + b + c + d);
      const Eigen::Vector3d outward = centre - (base + axis_up * axis_up.dot(centre - base));
      const Eigen::Vector3d along = (b - a).norm() > 1e-9 ? (b - a).normalized() : (c - d).normalized();
      const Eigen::Vector3d origin = a - (k * side_length) * along - rings[r].height * axis_up;
      const bool triangles = jitter > 0.0 || rings[r].radius <= 0.0 || rings[r + 1].radius <= 0.0;
      if (!triangles) {
        addPolygon(out, {a, b, c, d}, outward, surface, origin, along, axis_up);
      } else {
        if (rings[r].radius > 0.0) addPolygon(out, {a, b, c}, outward, surface, origin, along, axis_up);
        if (rings[r + 1].radius > 0.0) addPolygon(out, {a, c, d}, outward, surface, origin, along, axis_up);
      }
    }
  }
  auto cap = [&](std::size_t r, const Eigen::Vector3d& outward) {
    if (rings[r].radius <= 0.0) return;
    addPolygon(out, grid[r].data(), sides, outward, surface, grid[r][0], pose.linear() * Eigen::Vector3d::UnitX(),
               pose.linear() * Eigen::Vector3d::UnitZ());
  };
  cap(rings.size() - 1, axis_up);
  cap(0, -axis_up);
}

Eigen::Isometry3d groundPose(const Eigen::Vector3d& position, double heading) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = Eigen::AngleAxisd(heading, Eigen::Vector3d::UnitY()).toRotationMatrix();
  pose.translation() = position;
  return pose;
}

}  // namespace synthetic
}  // namespace semantic_edge_vo
