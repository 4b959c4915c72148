#include "semantic_edge_vo/backend/road_plane.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <sstream>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include "semantic_edge_vo/backend/keyframe.h"

namespace semantic_edge_vo {
namespace {

constexpr double kDegrees = M_PI / 180.0;

struct Plane {
  Eigen::Vector3d down;
  double height;
};

/// The points within the band of the plane, and the sum of their squared distances.
std::vector<int> inliersOf(const std::vector<Eigen::Vector3d>& points, const Plane& plane, double band, double* squared_sum) {
  std::vector<int> inliers;
  *squared_sum = 0.0;
  const double limit = band * plane.height;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const double distance = plane.down.dot(points[i]) - plane.height;
    if (std::abs(distance) > limit) continue;
    inliers.push_back(static_cast<int>(i));
    *squared_sum += distance * distance;
  }
  return inliers;
}

/// The plane with normal towards `down`, or false when it leans too far from it or lies above the camera.
bool orient(Eigen::Vector3d normal, const Eigen::Vector3d& through, const Eigen::Vector3d& down, double cos_max_deviation, Plane* plane) {
  if (normal.dot(down) < 0.0) normal = -normal;
  if (normal.dot(down) < cos_max_deviation) return false;
  plane->down = normal;
  plane->height = normal.dot(through);
  return plane->height > 0.0;
}

/// Least-squares plane through the inliers: their centroid and the direction they spread least in.
bool leastSquaresPlane(const std::vector<Eigen::Vector3d>& points, const std::vector<int>& inliers, const Eigen::Vector3d& down,
                       double cos_max_deviation, Plane* plane) {
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (int i : inliers) centroid += points[static_cast<std::size_t>(i)];
  centroid /= static_cast<double>(inliers.size());
  Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
  for (int i : inliers) {
    const Eigen::Vector3d d = points[static_cast<std::size_t>(i)] - centroid;
    scatter += d * d.transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(scatter);
  return orient(solver.eigenvectors().col(0), centroid, down, cos_max_deviation, plane);  // eigenvalues ascend
}

}  // namespace

Eigen::Vector3d RoadScaleOptions::expectedDown() const {
  const double pitch = pitch_deg * kDegrees, roll = roll_deg * kDegrees;
  return Eigen::Vector3d(std::sin(roll) * std::cos(pitch), std::cos(roll) * std::cos(pitch), std::sin(pitch));
}

void RoadScaleOptions::setMounting(const Eigen::Matrix3d& R_base_cam) {
  const Eigen::Vector3d down = R_base_cam.transpose() * -Eigen::Vector3d::UnitZ();  // expectedDown() of these angles
  pitch_deg = std::asin(std::clamp(down.z(), -1.0, 1.0)) / kDegrees;
  roll_deg = std::atan2(down.x(), down.y()) / kDegrees;
}

std::string RoadScaleOptions::validate() const {
  std::ostringstream error;
  if (!(camera_height >= 0.0)) error << "camera_height must be >= 0 m (0: no metric scale), got " << camera_height;
  else if (!(std::abs(pitch_deg) < 60.0 && std::abs(roll_deg) < 60.0))
    error << "road/pitch and road/roll must be within 60 deg of level (a camera that sees the road ahead)";
  else if (!(max_normal_deviation_deg > 0.0 && max_normal_deviation_deg < 45.0)) error << "road/max_normal_deviation must be in (0, 45) deg";
  else if (!(min_ahead > 0.0 && max_ahead > min_ahead && half_width > 0.0 && lane_half_width > 0.0))
    error << "road region: need 0 < min_ahead < max_ahead and half widths > 0 (camera heights)";
  else if (!(inlier_band > 0.0 && inlier_band < 1.0 && min_inliers >= 3 && min_inlier_ratio >= 0.0 && min_inlier_ratio <= 1.0 &&
             ransac_iterations >= 1 && height_sigma > 0.0 && scale_sigma > 0.0 && max_height_change > 0.0))
    error << "road fit: need 0 < inlier_band < 1, min_inliers >= 3, min_inlier_ratio in [0, 1], ransac_iterations >= 1, "
             "height_sigma and scale_sigma > 0, max_height_change > 0";
  return error.str();
}

std::uint32_t roadClassBits(const std::vector<std::string>& class_names) {
  for (std::size_t i = 0; i < class_names.size() && i < 32; ++i)
    if (class_names[i] == "road") return 1u << i;
  return 0;
}

bool RoadPlaneFinder::isEvidence(float u, float v, std::uint32_t class_mask) const {
  const std::uint32_t road = options_.road_classes;
  const bool road_only = road != 0 && class_mask != 0 && (class_mask & ~road) == 0;
  // The lane ahead is mostly road: every point there without classes; with classes its points of no
  // class (road texture) and its edges that touch the road (a marking, a kerb's foot), which keep
  // the fit going where road-class edges are few. What stands in the lane is an outlier to the fit.
  const bool lane_kind = road == 0 || class_mask == 0 || (class_mask & road) != 0;
  if (!road_only && !lane_kind) return false;
  const Eigen::Vector3d ray((u - camera_.cx) / camera_.fx, (v - camera_.cy) / camera_.fy, 1.0);
  double distance = 0.0, lateral = 0.0;
  if (!placeOnRoad(ray, &distance, &lateral) || distance < options_.min_ahead || distance > options_.max_ahead) return false;
  return (road_only && lateral <= options_.half_width) || (lane_kind && lateral <= options_.lane_half_width);
}

bool RoadPlaneFinder::inLaneAhead(const Eigen::Vector3d& ray) const {
  double distance = 0.0, lateral = 0.0;
  return placeOnRoad(ray, &distance, &lateral) && distance >= options_.min_ahead && distance <= options_.max_ahead &&
         lateral <= options_.lane_half_width;
}

bool RoadPlaneFinder::placeOnRoad(const Eigen::Vector3d& ray, double* ahead, double* lateral) const {
  const Eigen::Vector3d down = options_.expectedDown();
  const double below = down.dot(ray);
  if (below <= 1e-6) return false;  // at or above the horizon (rays of z = 1)
  const Eigen::Vector3d on_road = ray / below;  // where the ray meets the predicted road, one camera height down
  const Eigen::Vector3d forward = (Eigen::Vector3d::UnitZ() - down.z() * down).normalized();
  *lateral = std::abs(on_road.dot(forward.cross(down)));
  *ahead = on_road.dot(forward);
  return true;
}

RoadFit RoadPlaneFinder::fit(const std::vector<Eigen::Vector3d>& points) const {
  RoadFit fit;
  fit.evidence = static_cast<int>(points.size());
  if (points.size() < 3 || fit.evidence < options_.min_inliers) return fit;
  const Eigen::Vector3d down = options_.expectedDown();
  const double cos_max_deviation = std::cos(options_.max_normal_deviation_deg * kDegrees);
  std::mt19937 random(1);  // fixed seed: the same points give the same fit
  std::uniform_int_distribution<std::size_t> pick(0, points.size() - 1);
  Plane best{down, 0.0};
  std::vector<int> best_inliers;
  double best_squared = 0.0;
  for (int iteration = 0; iteration < options_.ransac_iterations; ++iteration) {
    const std::size_t a = pick(random), b = pick(random), c = pick(random);
    if (a == b || b == c || a == c) continue;
    const Eigen::Vector3d normal = (points[b] - points[a]).cross(points[c] - points[a]);
    if (normal.norm() < 1e-12) continue;
    Plane plane;
    if (!orient(normal.normalized(), points[a], down, cos_max_deviation, &plane)) continue;
    double squared = 0.0;
    std::vector<int> inliers = inliersOf(points, plane, options_.inlier_band, &squared);
    if (inliers.size() > best_inliers.size() || (inliers.size() == best_inliers.size() && squared < best_squared)) {
      best = plane;
      best_inliers = std::move(inliers);
      best_squared = squared;
    }
  }
  if (static_cast<int>(best_inliers.size()) < std::max(3, options_.min_inliers)) return fit;
  for (int round = 0; round < 3; ++round) {  // least squares on the inliers, then the inliers of that plane
    Plane refined;
    if (!leastSquaresPlane(points, best_inliers, down, cos_max_deviation, &refined)) break;
    double squared = 0.0;
    std::vector<int> inliers = inliersOf(points, refined, options_.inlier_band, &squared);
    if (static_cast<int>(inliers.size()) < options_.min_inliers) break;
    best = refined;
    best_inliers = std::move(inliers);
    best_squared = squared;
  }
  fit.down = best.down;
  fit.height = best.height;
  fit.inliers = std::move(best_inliers);
  fit.found = static_cast<int>(fit.inliers.size()) >= options_.min_inliers &&
              static_cast<double>(fit.inliers.size()) >= options_.min_inlier_ratio * fit.evidence;
  return fit;
}

bool RoadPlaneFinder::agreesWithMetres(double height) const {
  return std::abs(std::log(height / options_.camera_height)) <= std::log1p(options_.max_height_change);
}

RoadFit RoadPlaneFinder::fitKeyframe(const std::vector<MapPoint>& points) const {
  std::vector<Eigen::Vector3d> evidence;
  for (const MapPoint& point : points)
    if (point.hasDepth() && isEvidence(point.u, point.v, point.class_mask))
      evidence.push_back(camera_.backProject(point.u, point.v, 1.0 / point.inverse_depth));
  return fit(evidence);
}

RoadFit RoadPlaneFinder::fitKeyframe(const Keyframe& keyframe) const {
  RoadFit from_points = fitKeyframe(keyframe.points);
  return from_points.found ? from_points : keyframe.road;
}

}  // namespace semantic_edge_vo
