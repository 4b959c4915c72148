#include "semantic_edge_vo/synthetic/props.h"

#include <cmath>

#include "semantic_edge_vo/synthetic/random.h"

namespace semantic_edge_vo {
namespace synthetic {
namespace {

// Cityscapes train ids.
constexpr std::uint8_t kBuilding = 2, kPole = 5, kTrafficLight = 6, kTrafficSign = 7, kVegetation = 8, kCar = 13,
                       kTruck = 14;

Eigen::Isometry3d offset(const Eigen::Isometry3d& pose, double x, double height, double z) {
  Eigen::Isometry3d moved = pose;
  moved.translation() = pose * Eigen::Vector3d(x, -height, z);
  return moved;
}

void addWheels(Polygons* out, const Eigen::Isometry3d& pose, double half_track, double radius, double width,
               const std::initializer_list<double>& axles, std::uint8_t class_id) {
  const Surface tyre{Material::kTyre, class_id, 0, false};
  // The lathe axis (up) turned to point along +x.
  const Eigen::Matrix3d sideways = Eigen::AngleAxisd(1.5707963267948966, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  for (double z : axles)
    for (double side : {-1.0, 1.0}) {
      Eigen::Isometry3d wheel = offset(pose, side > 0 ? half_track - width : -half_track, radius, z);
      wheel.linear() = pose.linear() * sideways;
      addLathe(out, wheel, {{0.0, radius}, {width, radius}}, 8, tyre);
    }
}

}  // namespace

void addCar(Polygons* out, const Eigen::Isometry3d& pose, std::uint32_t variant) {
  const Surface paint{Material::kCarPaint, kCar, variant, false};
  const Surface glass{Material::kCarGlass, kCar, variant, false};
  addBox(out, offset(pose, 0.0, 0.3, 0.0), {1.8, 0.72, 4.3}, BoxSurfaces::uniform(paint));
  addBox(out, offset(pose, 0.0, 1.02, -0.25), {1.6, 0.46, 2.3}, {{glass, glass, glass, glass, paint}});
  addWheels(out, pose, 0.92, 0.32, 0.22, {1.35, -1.35}, kCar);
}

void addTruck(Polygons* out, const Eigen::Isometry3d& pose, std::uint32_t variant) {
  const Surface body{Material::kTruck, kTruck, variant, false};
  const Surface glass{Material::kCarGlass, kTruck, variant, false};
  const Surface cab{Material::kCarPaint, kTruck, variant, false};
  addBox(out, offset(pose, 0.0, 0.5, 4.6), {2.45, 1.3, 2.2}, BoxSurfaces::uniform(cab));
  addBox(out, offset(pose, 0.0, 1.8, 4.6), {2.45, 1.1, 2.2}, {{cab, cab, glass, cab, cab}});
  addBox(out, offset(pose, 0.0, 1.0, -1.4), {2.5, 3.0, 9.4}, BoxSurfaces::uniform(body));
  addWheels(out, pose, 1.2, 0.5, 0.35, {4.6, -3.0, -4.4}, kTruck);
}

void addTree(Polygons* out, const Eigen::Isometry3d& pose, double height, double crown_radius, bool conifer,
             std::uint32_t variant) {
  const Surface bark{Material::kBark, kVegetation, variant, false};
  const Surface leaves{Material::kFoliage, kVegetation, variant, false};
  const double trunk_radius = 0.08 + 0.02 * height;
  if (conifer) {
    addLathe(out, pose, {{0.0, trunk_radius}, {0.25 * height, trunk_radius}}, 5, bark);
    addLathe(out, pose, {{0.2 * height, crown_radius}, {0.6 * height, 0.55 * crown_radius}, {height, 0.0}}, 8, leaves,
             0.18, variant);
    return;
  }
  const double crown_bottom = 0.4 * height, crown_height = height - crown_bottom;
  addLathe(out, pose, {{0.0, trunk_radius}, {crown_bottom + 0.3 * crown_height, 0.7 * trunk_radius}}, 5, bark);
  addLathe(out, pose,
           {{crown_bottom, 0.0},
            {crown_bottom + 0.15 * crown_height, 0.75 * crown_radius},
            {crown_bottom + 0.45 * crown_height, crown_radius},
            {crown_bottom + 0.8 * crown_height, 0.7 * crown_radius},
            {height, 0.0}},
           8, leaves, 0.22, variant);
}

void addPole(Polygons* out, const Eigen::Isometry3d& pose, double height, double radius, bool wooden) {
  addLathe(out, pose, {{0.0, radius}, {height, 0.85 * radius}}, 6,
           {wooden ? Material::kWood : Material::kMetal, kPole, 0, false});
}

void addStreetLamp(Polygons* out, const Eigen::Isometry3d& pose, double height) {
  const Surface metal{Material::kMetal, kPole, 0, false};
  addPole(out, pose, height, 0.09, false);
  addBox(out, offset(pose, -0.9, height - 0.15, 0.0), {1.8, 0.1, 0.12}, BoxSurfaces::uniform(metal));
  addBox(out, offset(pose, -1.9, height - 0.3, 0.0), {0.6, 0.18, 0.3}, BoxSurfaces::uniform(metal));
}

void addSign(Polygons* out, const Eigen::Isometry3d& pose, double elevation, double width, double height, int posts,
             std::uint32_t variant) {
  const Surface face{Material::kSign, kTrafficSign, variant, false};
  const Surface edge{Material::kMetal, kTrafficSign, variant, false};
  for (int i = 0; i < posts; ++i) {
    const double x = posts == 1 ? 0.0 : width * (0.3 + 0.4 * i / (posts - 1) - 0.5);
    addPole(out, offset(pose, x, 0.0, 0.06), elevation + 0.8 * height, 0.045 + 0.02 * (posts - 1), false);
  }
  addBox(out, offset(pose, 0.0, elevation, 0.0), {width, height, 0.05}, {{edge, edge, face, face, edge}});
}

void addTrafficLight(Polygons* out, const Eigen::Isometry3d& pose, std::uint32_t variant) {
  const Surface housing{Material::kTrafficLight, kTrafficLight, variant, false};
  const Surface dark{Material::kMetal, kTrafficLight, variant, false};
  addPole(out, pose, 2.9, 0.06, false);
  addBox(out, offset(pose, 0.0, 2.9, 0.0), {0.34, 0.9, 0.3}, {{dark, dark, dark, housing, dark}});
}

void addBuilding(Polygons* out, const Eigen::Isometry3d& pose, double width, double height, double length,
                 std::uint32_t variant) {
  const Surface wall{Material::kFacade, kBuilding, variant, false};
  const Surface roof{Material::kRoof, kBuilding, variant, false};
  addBox(out, pose, {width, height, length}, {{wall, wall, wall, wall, roof}});
}

void addHouse(Polygons* out, const Eigen::Isometry3d& pose, double width, double wall_height, double length,
              std::uint32_t variant) {
  const Surface wall{Material::kHouseWall, kBuilding, variant, false};
  const Surface roof{Material::kRoof, kBuilding, variant, false};
  addBox(out, pose, {width, wall_height, length}, {{wall, wall, wall, wall, roof}});
  addGableRoof(out, pose, width + 0.6, length + 0.6, wall_height, wall_height + 0.45 * width, roof, wall);
}

}  // namespace synthetic
}  // namespace semantic_edge_vo
