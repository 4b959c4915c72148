#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "semantic_edge_vo/synthetic/random.h"

namespace semantic_edge_vo {
namespace synthetic {

/// Shape of a road centreline: straights and turns joined by clothoids (curvature ramps).
struct RouteOptions {
  double min_straight = 40.0;     ///< straight length, m
  double max_straight = 160.0;    ///< m
  double min_radius = 30.0;       ///< turn radius, m
  double max_radius = 70.0;       ///< m
  double min_turn = 0.6;          ///< heading change of a turn, rad
  double max_turn = 1.3;          ///< rad
  double transition = 12.0;       ///< clothoid length at each end of a turn, m
  double max_heading = 1.4;       ///< |heading| stays below this (rad < pi/2): the route never folds back

  std::string validate() const;
};

/// One point of the centreline in the map frame (x right, y down, z forward at the start; the road
/// surface is the plane y = 0).
struct RoutePoint {
  Eigen::Vector3d position;  ///< on the road surface (y = 0), m
  Eigen::Vector3d tangent;   ///< unit direction of travel
  Eigen::Vector3d right;     ///< unit, horizontal, to the right of travel
  double heading = 0.0;      ///< rad, 0 along +z, positive towards +x (right)
  double curvature = 0.0;    ///< 1/m, positive in right turns
};

/// A procedural road centreline, extended on demand: the first kilometres are the same whatever
/// length is asked for later, so a seed names one road of any length.
class Route {
 public:
  static constexpr double kStep = 0.25;  ///< spacing of the stored samples, m

  Route(const RouteOptions& options, std::uint64_t seed);

  /// Makes the centreline at least `length` metres long.
  void ensureLength(double length);
  double length() const { return static_cast<double>(samples_.size() - 1) * kStep; }
  /// The point at arc length s (0 <= s; extends the route when needed).
  RoutePoint at(double s);
  /// The point at arc length s of the part built already (s <= length()).
  RoutePoint at(double s) const;
  /// Smallest horizontal distance from `point` to the centreline between arc lengths s0 and s1, m.
  double distanceToCentreline(const Eigen::Vector3d& point, double s0, double s1) const;

 private:
  struct Sample {
    double x, z, heading, curvature;
  };
  void appendPiece();
  void appendCurvatureRamp(double length, double from, double to);

  RouteOptions options_;
  Random random_;
  std::vector<Sample> samples_;
};

}  // namespace synthetic
}  // namespace semantic_edge_vo
