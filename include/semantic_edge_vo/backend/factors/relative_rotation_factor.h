#pragma once
#include <ceres/sized_cost_function.h>

#include "semantic_edge_vo/backend/factors/pose_parameters.h"

namespace semantic_edge_vo {
namespace factors {

/// A measured rotation between two keyframes: residual log(R_measured^T R_earlier_later) / sigma
/// (radians), 3 components.
class RelativeRotationFactor : public ceres::SizedCostFunction<3, 7, 7> {
 public:
  RelativeRotationFactor(const Eigen::Matrix3d& R_earlier_later, double sigma) : measured_(R_earlier_later), weight_(1.0 / sigma) {}

  bool Evaluate(const double* const* parameters, double* residuals, double** jacobians) const override {
    const Eigen::Matrix3d R_earlier = fromParameters(parameters[0]).linear(), R_later = fromParameters(parameters[1]).linear();
    const Eigen::AngleAxisd error(measured_.transpose() * R_earlier.transpose() * R_later);
    const Eigen::Vector3d phi = error.angle() * error.axis();
    Eigen::Map<Eigen::Vector3d> residual(residuals);
    residual = weight_ * phi;
    if (!jacobians) return true;
    // log(M exp(w)) moves by Jr^-1(phi) w; log(R_m^T exp(-w) R_m M) = log(exp(-R_m^T w) M) by -Jl^-1(phi) R_m^T w.
    const double angle = error.angle();
    if (angle > M_PI - 1e-3) return false;  // turned half way round: the Jacobians are singular
    const double c = angle < 1e-4 ? 1.0 / 12.0 : 1.0 / (angle * angle) - (1.0 + std::cos(angle)) / (2.0 * angle * std::sin(angle));
    const Eigen::Matrix3d K = skew(phi), K2 = c * K * K;
    if (jacobians[0]) {
      Eigen::Map<Eigen::Matrix<double, 3, 7, Eigen::RowMajor>> J(jacobians[0]);
      J.setZero();
      J.middleCols<3>(3) = -weight_ * (Eigen::Matrix3d::Identity() - 0.5 * K + K2) * measured_.transpose();
    }
    if (jacobians[1]) {
      Eigen::Map<Eigen::Matrix<double, 3, 7, Eigen::RowMajor>> J(jacobians[1]);
      J.setZero();
      J.middleCols<3>(3) = weight_ * (Eigen::Matrix3d::Identity() + 0.5 * K + K2);
    }
    return true;
  }

 private:
  Eigen::Matrix3d measured_;
  double weight_;
};

}  // namespace factors
}  // namespace semantic_edge_vo
