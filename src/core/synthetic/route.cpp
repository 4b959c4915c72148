#include "semantic_edge_vo/synthetic/route.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace semantic_edge_vo {
namespace synthetic {

std::string RouteOptions::validate() const {
  std::ostringstream error;
  if (!(min_straight > 0.0 && max_straight >= min_straight))
    error << "need 0 < min_straight <= max_straight (got " << min_straight << ", " << max_straight << ")";
  else if (!(min_radius > 0.0 && max_radius >= min_radius))
    error << "need 0 < min_radius <= max_radius (got " << min_radius << ", " << max_radius << ")";
  else if (!(min_turn > 0.0 && max_turn >= min_turn))
    error << "need 0 < min_turn <= max_turn, rad (got " << min_turn << ", " << max_turn << ")";
  else if (!(transition > 0.0)) error << "transition must be > 0 m (got " << transition << ")";
  else if (!(max_heading > 0.0 && max_heading < 1.5707963))
    error << "max_heading must be in (0, pi/2) rad (got " << max_heading << ")";
  return error.str();
}

Route::Route(const RouteOptions& options, std::uint64_t seed) : options_(options), random_(hashCombine(seed, 0x726f757465ULL)) {
  samples_.push_back({0.0, 0.0, 0.0, 0.0});
  // Start on a straight, so the first frames look along the road.
  appendCurvatureRamp(options_.min_straight, 0.0, 0.0);
}

void Route::appendCurvatureRamp(double length, double from, double to) {
  const int steps = std::max(1, static_cast<int>(std::lround(length / kStep)));
  for (int i = 1; i <= steps; ++i) {
    const Sample& last = samples_.back();
    const double curvature = from + (to - from) * i / steps;
    // Midpoint rule: the heading half-way through the step gives the chord direction.
    const double mid_heading = last.heading + 0.5 * kStep * 0.5 * (last.curvature + curvature);
    samples_.push_back({last.x + kStep * std::sin(mid_heading), last.z + kStep * std::cos(mid_heading),
                        last.heading + kStep * 0.5 * (last.curvature + curvature), curvature});
  }
}

void Route::appendPiece() {
  const double heading = samples_.back().heading;
  // Turn back towards the start direction more often, and never past max_heading.
  double direction = random_.chance(0.5 + 0.4 * std::tanh(2.0 * heading)) ? -1.0 : 1.0;
  double turn = random_.uniform(options_.min_turn, options_.max_turn);
  if (std::abs(heading + direction * turn) > options_.max_heading) direction = -direction;
  turn = std::min(turn, options_.max_heading - direction * heading);
  const double radius = random_.uniform(options_.min_radius, options_.max_radius);
  const double curvature = direction / radius;
  // Heading change: the two ramps turn by curvature * transition together, the arc by the rest.
  const double ramp = std::min(options_.transition, turn * radius);
  const double arc = std::max(0.0, turn * radius - ramp);
  appendCurvatureRamp(ramp, 0.0, curvature);
  if (arc > 0.0) appendCurvatureRamp(arc, curvature, curvature);
  appendCurvatureRamp(ramp, curvature, 0.0);
  appendCurvatureRamp(random_.uniform(options_.min_straight, options_.max_straight), 0.0, 0.0);
}

void Route::ensureLength(double length) {
  while (this->length() < length) appendPiece();
}

RoutePoint Route::at(double s) {
  ensureLength(s + 1.0);
  return static_cast<const Route&>(*this).at(s);
}

RoutePoint Route::at(double s) const {
  const double position = std::clamp(s / kStep, 0.0, static_cast<double>(samples_.size() - 1));
  const std::size_t i = std::min(static_cast<std::size_t>(position), samples_.size() - 2);
  const double t = position - static_cast<double>(i);
  const Sample& a = samples_[i];
  const Sample& b = samples_[i + 1];
  RoutePoint point;
  point.heading = a.heading + t * (b.heading - a.heading);
  point.curvature = a.curvature + t * (b.curvature - a.curvature);
  point.position = {a.x + t * (b.x - a.x), 0.0, a.z + t * (b.z - a.z)};
  point.tangent = {std::sin(point.heading), 0.0, std::cos(point.heading)};
  point.right = {std::cos(point.heading), 0.0, -std::sin(point.heading)};
  return point;
}

double Route::distanceToCentreline(const Eigen::Vector3d& point, double s0, double s1) const {
  const auto first = static_cast<std::size_t>(std::max(0.0, s0 / kStep));
  const auto last = std::min(samples_.size() - 1, static_cast<std::size_t>(std::max(0.0, s1 / kStep)));
  double best = 1e300;
  for (std::size_t i = first; i <= last; i += 4) {  // 1 m spacing is plenty for keep-out tests
    const double dx = samples_[i].x - point.x(), dz = samples_[i].z - point.z();
    best = std::min(best, dx * dx + dz * dz);
  }
  return std::sqrt(best);
}

}  // namespace synthetic
}  // namespace semantic_edge_vo
