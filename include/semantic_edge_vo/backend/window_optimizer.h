#pragma once
#include <deque>
#include <functional>
#include <memory>
#include <string>

#include "semantic_edge_vo/backend/factors/observation_weights.h"
#include "semantic_edge_vo/frontend/forward_motion_prior.h"
#include "semantic_edge_vo/backend/keyframe.h"
#include "semantic_edge_vo/backend/road_plane.h"

namespace semantic_edge_vo {

struct WindowOptimizerOptions {
  int keyframes = 5;               ///< newest keyframes optimised together (the oldest of them is held fixed)
  int max_iterations = 4;          ///< Levenberg-Marquardt iterations per solve (few: the window keeps up live)
  int point_stride = 2;            ///< every n-th point of each host keyframe takes part
  double photometric_sigma = 4.0;  ///< gray levels / px (gradient magnitude)
  double photometric_huber = 9.0;  ///< gray levels / px
  double edge_sigma = 1.0;         ///< px
  double edge_huber = 1.5;         ///< px
  double edge_weight = 0.5;        ///< mapping weighs edges less than tracking (paper III-C)
  double edge_radius = 3.0;        ///< an edge point is associated with an edge of a shared class this near, px
  /// Sigma of each inverse-depth prior in units of the point's filtered sigma. The filter's depths
  /// come from one chain of tracked poses and inherit its errors (a yaw error leaves a left-right
  /// depth gradient that feeds the next yaw error); a loose prior lets the window correct them.
  double depth_prior_scale = 100.0;
  /// Between consecutive keyframes (the loader sets the tracker's): the window would otherwise
  /// re-learn the lateral drift the tracker's prior holds back, from depths that agree with it.
  ForwardMotionOptions forward_motion;
  /// Sigmas of the priors on a keyframe's rotation and direction of travel from the keyframe before
  /// it where two-view geometry measured them (Keyframe::measured_motion), deg; 0: not used. The
  /// direct residuals leave the direction of travel weakly observed under forward motion (a shifted
  /// focus of expansion with depths to match explains them nearly as well): corners tracked between
  /// the keyframes measure it independently of the depths.
  double measured_rotation_sigma_deg = 0.05;
  double measured_direction_sigma_deg = 0.5;

  std::string validate() const;
  /// The sigmas, thresholds and edge weight of the point observations' rows.
  factors::ObservationWeights observationWeights() const;
};

struct WindowOptimizerResult {
  int keyframes = 0, points = 0, photometric_residuals = 0, edge_residuals = 0;
  double initial_cost = 0.0, final_cost = 0.0;
  bool solved = false;
  /// Metric scale (RoadScaleOptions::enabled): keyframes whose road plane measured the scale, and
  /// the scale the window took towards the road (1: held).
  int road_keyframes = 0;
  double scale_step = 1.0;
};

/// Windowed optimisation of keyframe poses and point inverse depths with Ceres (paper III-C):
/// photometric residuals (gradient magnitude, Huber) of every point in every other keyframe of the
/// window, point-to-tangent residuals of edge points against their nearest same-class edge there
/// (smaller weight than in tracking), and a prior on each inverse depth at its filtered estimate and
/// sigma, priors on the motion between consecutive keyframes (forward travel; measured rotation and
/// direction). The oldest keyframe of the window is held fixed (gauge).
/// With a camera height, the road under each keyframe (RoadPlaneFinder) measures the map's scale
/// there, and the window's cost has a term for each such measurement and a prior on the change of
/// scale in one solve (RoadScaleOptions::height_sigma, scale_sigma). Every other term is unchanged
/// by scaling the window about its held keyframe (positions and depths together), and the solver's
/// damped steps do not find that direction: so the cost is first minimised along it, in closed
/// form, then the rest is solved.
class WindowOptimizer {
 public:
  WindowOptimizer(const WindowOptimizerOptions& options, const RoadScaleOptions& road = {}) : options_(options), road_(road) {}
  /// Optimises the newest keyframes of `window` in place. When `stop` is given and returns true
  /// after an iteration (from the first on), the solve ends there with the last solution the solver accepted.
  WindowOptimizerResult optimize(const std::deque<std::shared_ptr<Keyframe>>& window,
                                 const std::function<bool()>& stop = nullptr) const;

 private:
  WindowOptimizerOptions options_;
  RoadScaleOptions road_;
};

}  // namespace semantic_edge_vo
