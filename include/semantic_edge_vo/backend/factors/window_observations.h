#pragma once
// The window's point observations: one Ceres residual block per (point, target keyframe) holding
// its photometric row, its edge row when it has an associated edge, and the point's inverse-depth
// prior on its first observation. Ceres' cost per residual block, not the residuals' arithmetic, was
// most of the window's time with one block per residual; and all blocks are evaluated together,
// on both cores, before Ceres asks for any of them (an EvaluationCallback), which Ceres' own
// threads cannot do deterministically.
#include <vector>

#include <ceres/cost_function.h>
#include <ceres/cubic_interpolation.h>
#include <ceres/evaluation_callback.h>

#include "semantic_edge_vo/common/camera.h"
#include "semantic_edge_vo/backend/factors/observation_weights.h"
#include "semantic_edge_vo/backend/factors/pose_parameters.h"

namespace semantic_edge_vo {
namespace factors {

using Interpolator = ceres::BiCubicInterpolator<ceres::Grid2D<float, 1>>;

/// A host point seen from a target keyframe of the window.
struct Observation {
  int host = 0, target = 0;                ///< indices into the window's poses
  Eigen::Vector3d host_ray;                ///< the host pixel on the z = 1 plane
  double host_value = 0.0;                 ///< host gradient magnitude at the pixel
  const double* inverse_depth = nullptr;   ///< the point's parameter block
  bool has_edge = false;                   ///< the nearest edge of a shared class, found before the solve:
  Eigen::Vector2d match = Eigen::Vector2d::Zero(), normal = Eigen::Vector2d::UnitX();  ///< its pixel and unit normal
  bool has_prior = false;                  ///< carries the point's inverse-depth prior (paper III-C)
  double prior = 0.0, prior_sigma = 1.0;   ///< (rho - prior) / prior_sigma
};

/// A residual r of cost w * Huber_k(r^2) (Ceres' HuberLoss(k) scaled by w) as Ceres' loss
/// functions present it to the solver (its Corrector, for a loss with rho'' <= 0): the row
/// sqrt(rho') r with its Jacobian scaled by sqrt(rho') (iteratively reweighted least squares), and the
/// rest of the cost, rho - rho' r^2 (0 for an inlier), which the linear model does not see. Ceres'
/// loss functions apply to a whole residual block; the rows of a block are robust each on its own.
struct RobustRow {
  double residual = 0.0, scale = 1.0, remainder = 0.0;
};
RobustRow robustRow(double r, double k, double w);

/// The observations of one solve. Ceres copies each evaluation point into the parameter blocks
/// before calling PrepareForEvaluation, which evaluates every observation (relative poses of the
/// keyframe pairs once, then the rows in fixed slices: the same numbers in every run); each cost
/// function then only copies its rows. Parameters of each block: host pose (7), target pose (7),
/// inverse depth (1); Jacobians in the poses' tangent spaces, padded as PoseManifold expects.
/// The robust rows' remainders (RobustRow) go to one more block, remainderBlock(): the solver
/// then sees the cost, gradient and Gauss-Newton model it saw with one loss function per residual.
/// The blocks hold the rows of the last evaluation (after a solve, maybe of a rejected step), so
/// anything evaluating them without the callback (Ceres' check_gradients) reads stale rows.
class WindowObservations : public ceres::EvaluationCallback {
 public:
  /// @param poses the window's pose parameter blocks; @param images each keyframe's gradient
  /// magnitude, parallel to poses; all outlive this
  WindowObservations(const std::vector<PoseParameters>& poses, std::vector<const Interpolator*> images, const PinholeCamera& camera,
                     const ObservationWeights& weights);

  /// Room for this many observations.
  void reserve(std::size_t count);
  /// The observation's residual block (1 to 3 rows) for the problem, which owns it; it reads this
  /// object's results, so this must outlive the solve.
  ceres::CostFunction* add(const Observation& observation);

  /// The block of one row, sqrt(sum of the remainders), with a zero Jacobian, on any pose that is
  /// not held constant (a block needs a parameter); owned by the problem, reads this object's results.
  ceres::CostFunction* remainderBlock() const;

  void PrepareForEvaluation(bool evaluate_jacobians, bool new_evaluation_point) override;

  struct Rows {
    bool valid = false;  ///< the point lies in front of the target camera
    double residuals[3] = {0.0, 0.0, 0.0};
    double remainder = 0.0;  ///< of the robust rows' costs
    Eigen::Matrix<double, 3, 6, Eigen::RowMajor> d_host, d_target;  ///< by each pose's twist (rows as Ceres copies them)
    Eigen::Vector3d d_rho;
  };
  const Rows& rows(std::size_t observation) const { return rows_[observation]; }
  double remainder() const { return remainder_; }  ///< of all observations' robust rows

 private:
  void evaluate(std::size_t index, bool with_jacobians);

  const std::vector<PoseParameters>& poses_;
  std::vector<const Interpolator*> images_;
  PinholeCamera camera_;
  ObservationWeights weights_;
  std::vector<Observation> observations_;
  std::vector<Rows> rows_;
  std::vector<PairTransform> pairs_;  ///< [host * poses + target], at the evaluation point
  double remainder_ = 0.0;
  bool have_jacobians_ = false;       ///< at the current evaluation point
};

}  // namespace factors
}  // namespace semantic_edge_vo
