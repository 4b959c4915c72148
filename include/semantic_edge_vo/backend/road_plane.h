#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "semantic_edge_vo/backend/map_point.h"
#include "semantic_edge_vo/common/camera.h"

namespace semantic_edge_vo {

struct Keyframe;

/// Metric scale from the road: the camera rides `camera_height` above it, so the height of the
/// road plane fitted to a keyframe's road points measures the map's scale at that keyframe.
struct RoadScaleOptions {
  double camera_height = 0.0;  ///< optical centre above the road, m; 0: scale unknown (the initialisation's)
  /// The camera's mounting relative to the road: pitch (+: looking down) and roll (+: right side
  /// down), deg. Fits whose normal leans farther than max_normal_deviation from it are rejected.
  double pitch_deg = 0.0, roll_deg = 0.0;
  double max_normal_deviation_deg = 6.0;
  /// Class bits of the road; 0: no classes (the Canny intake).
  std::uint32_t road_classes = 0;
  /// Where road points are taken, on the road plane the mounting predicts, in camera heights: ahead
  /// of the camera from min_ahead to max_ahead; edges of the road class alone up to `half_width` to
  /// either side; in the lane ahead (`lane_half_width`) also points of no class and edges touching
  /// the road, and without classes every point (whatever stands there is an outlier to the fit).
  double min_ahead = 2.0, max_ahead = 10.0, half_width = 4.0, lane_half_width = 1.2;
  double inlier_band = 0.05;     ///< a point within this fraction of the height of the plane is on it
  int min_inliers = 15;          ///< a fit needs this many points on the plane
  double min_inlier_ratio = 0.3; ///< ... and this fraction of the evidence
  int ransac_iterations = 150;
  /// Sigma of one keyframe's road height as a measurement of the map's scale, fraction.
  double height_sigma = 0.05;
  /// Sigma of the change of scale the road may make in one windowed optimisation (one keyframe),
  /// fraction: the odometry's own scale holds from keyframe to keyframe far better than one road
  /// fit measures it, so the road corrects the drift over many keyframes.
  double scale_sigma = 0.01;
  /// Once the map is in metres, a plane this far from the camera's height (fraction) is taken for a
  /// wrong fit (a crest, a car's flank, classes on a wall) and not used: the scale is held.
  double max_height_change = 0.15;

  bool enabled() const { return camera_height > 0.0; }
  /// Sets pitch and roll from the camera's orientation on the vehicle (R_base_cam: optical frame to
  /// a REP-103 base frame, z up), as tf gives it.
  void setMounting(const Eigen::Matrix3d& R_base_cam);
  /// The road's downward unit normal in the optical frame the mounting predicts.
  Eigen::Vector3d expectedDown() const;
  std::string validate() const;
};

/// The class bit of "road" in a class table's names; 0 when it has none (the Canny intake's "edge").
std::uint32_t roadClassBits(const std::vector<std::string>& class_names);

/// A plane n . X = height under the camera, in a keyframe's optical frame.
struct RoadFit {
  bool found = false;
  Eigen::Vector3d down = Eigen::Vector3d::UnitY();  ///< unit normal, pointing from the camera to the road
  double height = 0.0;       ///< the camera's distance from the plane, map units
  int evidence = 0;          ///< road points offered
  std::vector<int> inliers;  ///< indices (into the points offered) on the plane
};

/// Finds the road plane under a keyframe, robustly (RANSAC over plane triples whose normal agrees
/// with the mounting, then least squares on the inliers).
class RoadPlaneFinder {
 public:
  RoadPlaneFinder(const RoadScaleOptions& options, const PinholeCamera& camera) : options_(options), camera_(camera) {}

  /// Whether a point at this pixel with these classes may lie on the road (before its depth is known).
  bool isEvidence(float u, float v, std::uint32_t class_mask) const;
  /// Whether a viewing ray (optical frame, z = 1) meets the road the mounting predicts in the lane
  /// ahead.
  bool inLaneAhead(const Eigen::Vector3d& ray) const;
  /// The plane through `points` (optical frame, map units); deterministic.
  RoadFit fit(const std::vector<Eigen::Vector3d>& points) const;
  /// Whether a plane this high (map units) measures a map already in metres (max_height_change).
  bool agreesWithMetres(double height) const;
  /// The plane under a keyframe, from its points with a measured depth that are road evidence.
  RoadFit fitKeyframe(const std::vector<MapPoint>& points) const;
  /// The plane under a keyframe: from its points where they give one (on real roads the more
  /// accurate), else its dense fit (Keyframe::road), which is found where the points scatter.
  RoadFit fitKeyframe(const Keyframe& keyframe) const;

 private:
  /// Where a ray meets the predicted road, in camera heights: ahead of the camera and to either
  /// side (absolute); false at or above the horizon.
  bool placeOnRoad(const Eigen::Vector3d& ray, double* ahead, double* lateral) const;

  RoadScaleOptions options_;
  PinholeCamera camera_;
};

}  // namespace semantic_edge_vo
