#pragma once
#include <array>
#include <cstdint>
#include <initializer_list>
#include <vector>

#include <Eigen/Geometry>

namespace semantic_edge_vo {
namespace synthetic {

/// Procedural surface appearance (see materials.h).
enum class Material : std::uint8_t {
  kAsphalt, kSidewalk, kCurb, kFacade, kHouseWall, kRoof, kCarPaint, kCarGlass, kTyre, kMetal,
  kSign, kTrafficLight, kFoliage, kBark, kGrass, kGuardRail, kConcrete, kWood, kTruck,
};

/// What a face looks like and which class it is.
struct Surface {
  Material material = Material::kConcrete;
  std::uint8_t class_id = 0;   ///< Cityscapes train id
  std::uint32_t variant = 0;   ///< per-object random bits: colour and layout choices of the material
  bool two_sided = false;      ///< visible from behind too (thin plates); closed solids are one-sided
};

/// A convex planar polygon with a surface parametrisation: a = (p - tex_origin) . tex_u and
/// b = (p - tex_origin) . tex_v (metres) are the texture coordinates, fixed to the surface.
struct Polygon {
  static constexpr int kMaxVertices = 8;
  std::array<Eigen::Vector3d, kMaxVertices> vertices;
  int vertex_count = 0;
  Eigen::Vector3d normal = Eigen::Vector3d::UnitY();  ///< unit, pointing to the side it is seen from
  Eigen::Vector3d tex_origin = Eigen::Vector3d::Zero();
  Eigen::Vector3d tex_u = Eigen::Vector3d::UnitX();
  Eigen::Vector3d tex_v = Eigen::Vector3d::UnitZ();
  float extent_a = 0.0f;  ///< size of the face along tex_u, m (layouts such as windows centre on it)
  float extent_b = 0.0f;  ///< size of the face along tex_v, m
  Surface surface;
  bool dynamic = false;   ///< part of a moving object

  /// Moves the polygon rigidly (vertices, normal, texture frame).
  void transform(const Eigen::Isometry3d& T);
};

using Polygons = std::vector<Polygon>;

/// Object frames follow the camera convention: x right, y down, z forward; objects stand on y = 0.
inline Eigen::Vector3d up() { return {0.0, -1.0, 0.0}; }

/// Appends a convex planar polygon; the normal is flipped to agree with `outward`.
void addPolygon(Polygons* out, std::initializer_list<Eigen::Vector3d> vertices, const Eigen::Vector3d& outward,
                const Surface& surface, const Eigen::Vector3d& tex_origin, const Eigen::Vector3d& tex_u,
                const Eigen::Vector3d& tex_v, float extent_a = 0.0f, float extent_b = 0.0f);
/// The same from an array of `count` (3..kMaxVertices) vertices.
void addPolygon(Polygons* out, const Eigen::Vector3d* vertices, int count, const Eigen::Vector3d& outward,
                const Surface& surface, const Eigen::Vector3d& tex_origin, const Eigen::Vector3d& tex_u,
                const Eigen::Vector3d& tex_v, float extent_a = 0.0f, float extent_b = 0.0f);

/// Surfaces of a box: sides seen from +x, -x, +z, -z, then the top.
struct BoxSurfaces {
  std::array<Surface, 5> faces;
  static BoxSurfaces uniform(const Surface& surface) { return {{surface, surface, surface, surface, surface}}; }
};

/// A box of size (width along x, height, length along z) standing on y = 0 of `pose`, centred on its
/// axis. Side faces are textured with a along the face (left to right seen from outside), b upwards.
void addBox(Polygons* out, const Eigen::Isometry3d& pose, const Eigen::Vector3d& size, const BoxSurfaces& surfaces);

/// A pitched roof over a width x length rectangle: eaves at height `eaves`, ridge along z at `ridge`.
void addGableRoof(Polygons* out, const Eigen::Isometry3d& pose, double width, double length, double eaves,
                  double ridge, const Surface& roof, const Surface& gable);

/// A ring of a solid of revolution: radius (m) at a height above the base (m).
struct Ring {
  double height;
  double radius;
};

/// A solid of revolution about the up axis of `pose` with `sides` (3..8) faces, caps where a ring at
/// an end has a radius. With jitter > 0 the vertex radii vary by up to that fraction (then the faces
/// are triangles, so they stay planar): ragged tree crowns.
void addLathe(Polygons* out, const Eigen::Isometry3d& pose, const std::vector<Ring>& rings, int sides,
              const Surface& surface, double jitter = 0.0, std::uint64_t jitter_seed = 0);

/// The pose of an object standing at `position` with its z axis along `heading` (rad, about the up
/// axis, 0 = map +z).
Eigen::Isometry3d groundPose(const Eigen::Vector3d& position, double heading);

}  // namespace synthetic
}  // namespace semantic_edge_vo
