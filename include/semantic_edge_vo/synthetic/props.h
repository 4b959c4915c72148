#pragma once
#include <cstdint>

#include <Eigen/Geometry>

#include "semantic_edge_vo/synthetic/scene_geometry.h"

namespace semantic_edge_vo {
namespace synthetic {

/// Street furniture and vehicles, each in its own frame (x right, y down, z forward, standing on
/// y = 0 of `pose`). Sizes in metres; `variant` picks colours and layouts.

/// A car of about 4.3 x 1.8 x 1.5 m facing +z: body, glass cabin, four wheels (class car).
void addCar(Polygons* out, const Eigen::Isometry3d& pose, std::uint32_t variant);
/// A truck of about 12 x 2.5 x 4 m facing +z: cab and box trailer (class truck).
void addTruck(Polygons* out, const Eigen::Isometry3d& pose, std::uint32_t variant);
/// A deciduous tree (ragged ellipsoid crown) or a conifer (cone), trunk included (class vegetation).
void addTree(Polygons* out, const Eigen::Isometry3d& pose, double height, double crown_radius, bool conifer,
             std::uint32_t variant);
/// A street lamp: pole with an arm reaching over the road along -x of `pose` (class pole).
void addStreetLamp(Polygons* out, const Eigen::Isometry3d& pose, double height);
/// A plain pole (class pole): `wooden` for village utility poles.
void addPole(Polygons* out, const Eigen::Isometry3d& pose, double height, double radius, bool wooden);
/// A sign plate of width x height with its lower edge at `elevation`, facing -z (towards traffic coming
/// along +z), on `posts` poles (class traffic sign plate, class pole posts).
void addSign(Polygons* out, const Eigen::Isometry3d& pose, double elevation, double width, double height, int posts,
             std::uint32_t variant);
/// A traffic light on a pole, lamps facing -z (class traffic light, class pole).
void addTrafficLight(Polygons* out, const Eigen::Isometry3d& pose, std::uint32_t variant);
/// A city block building: flat roof, facades with windows (class building).
void addBuilding(Polygons* out, const Eigen::Isometry3d& pose, double width, double height, double length,
                 std::uint32_t variant);
/// A village house: plastered walls, pitched roof (class building).
void addHouse(Polygons* out, const Eigen::Isometry3d& pose, double width, double wall_height, double length,
              std::uint32_t variant);

}  // namespace synthetic
}  // namespace semantic_edge_vo
