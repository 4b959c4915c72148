#include "semantic_edge_vo/backend/factors/window_observations.h"

#include <algorithm>
#include <cmath>

#include <ceres/sized_cost_function.h>

#include "semantic_edge_vo/common/parallel_slices.h"

namespace semantic_edge_vo {
namespace factors {
namespace {

/// Copies the rows WindowObservations evaluated for one observation.
class ObservationFactor : public ceres::CostFunction {
 public:
  ObservationFactor(const WindowObservations& owner, std::size_t index, int rows) : owner_(owner), index_(index) {
    set_num_residuals(rows);
    *mutable_parameter_block_sizes() = {7, 7, 1};
  }

  bool Evaluate(const double* const*, double* residuals, double** jacobians) const override {
    const WindowObservations::Rows& rows = owner_.rows(index_);
    if (!rows.valid) return false;
    const int count = num_residuals();
    std::copy(rows.residuals, rows.residuals + count, residuals);
    if (!jacobians) return true;
    for (int row = 0; row < count; ++row) {
      if (jacobians[0]) {  // null for the fixed keyframe
        Eigen::Map<Eigen::Matrix<double, 1, 7>> host(jacobians[0] + 7 * row);
        host << rows.d_host.row(row), 0.0;
      }
      if (jacobians[1]) {
        Eigen::Map<Eigen::Matrix<double, 1, 7>> target(jacobians[1] + 7 * row);
        target << rows.d_target.row(row), 0.0;
      }
      if (jacobians[2]) jacobians[2][row] = rows.d_rho(row);
    }
    return true;
  }

 private:
  const WindowObservations& owner_;
  std::size_t index_;
};

/// The robust rows' remainders as one row; its Jacobian is zero (the linear model leaves them out).
class RemainderFactor : public ceres::SizedCostFunction<1, 7> {
 public:
  explicit RemainderFactor(const WindowObservations& owner) : owner_(owner) {}

  bool Evaluate(const double* const*, double* residuals, double** jacobians) const override {
    residuals[0] = std::sqrt(owner_.remainder());
    if (jacobians && jacobians[0]) std::fill(jacobians[0], jacobians[0] + 7, 0.0);
    return true;
  }

 private:
  const WindowObservations& owner_;
};

}  // namespace

RobustRow robustRow(double r, double k, double w) {
  const double magnitude = std::abs(r);
  RobustRow row;
  if (magnitude <= k) {  // rho = w r^2
    row.scale = std::sqrt(w);
  } else {  // rho = w (2 k |r| - k^2), rho' = w k / |r|
    row.scale = std::sqrt(w * k / magnitude);
    row.remainder = w * k * (magnitude - k);
  }
  row.residual = row.scale * r;
  return row;
}

WindowObservations::WindowObservations(const std::vector<PoseParameters>& poses, std::vector<const Interpolator*> images,
                                       const PinholeCamera& camera, const ObservationWeights& weights)
    : poses_(poses), images_(std::move(images)), camera_(camera), weights_(weights), pairs_(poses.size() * poses.size()) {}

void WindowObservations::reserve(std::size_t count) {
  observations_.reserve(count);
  rows_.reserve(count);
}

ceres::CostFunction* WindowObservations::add(const Observation& observation) {
  observations_.push_back(observation);
  rows_.emplace_back();
  const int rows = 1 + observation.has_edge + observation.has_prior;
  return new ObservationFactor(*this, observations_.size() - 1, rows);
}

ceres::CostFunction* WindowObservations::remainderBlock() const { return new RemainderFactor(*this); }

void WindowObservations::PrepareForEvaluation(bool evaluate_jacobians, bool new_evaluation_point) {
  // After a residual-only evaluation Ceres may ask for the Jacobians at the same point.
  if (!new_evaluation_point && (have_jacobians_ || !evaluate_jacobians)) return;
  const std::size_t count = poses_.size();
  for (std::size_t host = 0; host < count; ++host)
    for (std::size_t target = 0; target < count; ++target)
      if (host != target) pairs_[host * count + target] = pairTransform(poses_[host].data(), poses_[target].data());
  forEachIndex(observations_.size(), [&](std::size_t i) { evaluate(i, evaluate_jacobians); });
  remainder_ = 0.0;  // in order: the same sum in every run
  for (const Rows& rows : rows_) remainder_ += rows.remainder;
  have_jacobians_ = evaluate_jacobians;
}

void WindowObservations::evaluate(std::size_t index, bool with_jacobians) {
  const Observation& observation = observations_[index];
  Rows& rows = rows_[index];
  const double rho = *observation.inverse_depth;
  const HostToTarget point(pairs_[static_cast<std::size_t>(observation.host) * poses_.size() + observation.target], rho,
                           observation.host_ray, with_jacobians);
  rows.valid = point.P.z() > 1e-6;
  rows.remainder = 0.0;
  if (!rows.valid) return;
  Eigen::Matrix<double, 2, 3> d_pixel;
  const Eigen::Vector2d pixel = project(point.P, camera_.fx, camera_.fy, camera_.cx, camera_.cy, &d_pixel);
  // Row `row` from a residual r(P), its derivative by P and its robust weighting.
  const auto setRow = [&](int row, const RobustRow& robust, const Eigen::RowVector3d& d_residual) {
    rows.residuals[row] = robust.residual;
    rows.remainder += robust.remainder;
    if (!with_jacobians) return;
    const Eigen::RowVector3d d = robust.scale * d_residual;
    rows.d_host.row(row) = d * point.d_host;
    rows.d_target.row(row) = d * point.d_target;
    rows.d_rho(row) = d.dot(point.d_rho);
  };

  // Photometric (paper III-C): the target's gradient magnitude at the projection minus the host's,
  // bicubic with its exact derivatives (beyond the border the image continues flat).
  double value = 0.0, d_row = 0.0, d_column = 0.0;
  images_[static_cast<std::size_t>(observation.target)]->Evaluate(pixel.y(), pixel.x(), &value, &d_row, &d_column);
  const double photometric_sigma = weights_.photometric_sigma, edge_sigma = weights_.edge_sigma;
  setRow(0, robustRow((value - observation.host_value) / photometric_sigma, weights_.photometric_huber / photometric_sigma, 1.0),
         Eigen::RowVector2d(d_column, d_row) * d_pixel / photometric_sigma);
  int row = 1;
  if (observation.has_edge)  // point to tangent: n . (projection - match)
    setRow(row++, robustRow(observation.normal.dot(pixel - observation.match) / edge_sigma, weights_.edge_huber / edge_sigma, weights_.edge_weight),
           observation.normal.transpose() * d_pixel / edge_sigma);
  if (observation.has_prior) {
    rows.residuals[row] = (rho - observation.prior) / observation.prior_sigma;
    if (!with_jacobians) return;
    rows.d_host.row(row).setZero();
    rows.d_target.row(row).setZero();
    rows.d_rho(row) = 1.0 / observation.prior_sigma;
  }
}

}  // namespace factors
}  // namespace semantic_edge_vo
