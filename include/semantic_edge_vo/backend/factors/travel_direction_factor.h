#pragma once
#include <ceres/sized_cost_function.h>

#include "semantic_edge_vo/backend/factors/pose_parameters.h"
#include "semantic_edge_vo/frontend/forward_motion_prior.h"

namespace semantic_edge_vo {
namespace factors {

/// The later keyframe's camera centre, seen from the earlier one, lies along a direction given in
/// the earlier one's optical frame. Residuals: its two components across the direction, divided by
/// the keyframes' distance and sigma (radians). The distance, and so the weight, is fixed at the
/// start of the solve: the residuals stay linear in the centre.
class TravelDirectionFactor : public ceres::SizedCostFunction<2, 7, 7> {
 public:
  TravelDirectionFactor(const Eigen::Vector3d& direction, double sigma, double distance) {
    const Eigen::Vector3d unit = direction.normalized();
    const Eigen::Vector3d e1 = unit.unitOrthogonal();
    const double scale = 1.0 / (sigma * std::max(distance, 1e-9));
    across_.row(0) = scale * e1.transpose();
    across_.row(1) = scale * unit.cross(e1).transpose();
  }

  bool Evaluate(const double* const* parameters, double* residuals, double** jacobians) const override {
    const Eigen::Isometry3d T_world_earlier = fromParameters(parameters[0]), T_world_later = fromParameters(parameters[1]);
    const Eigen::Matrix3d R_earlier_world = T_world_earlier.linear().transpose();
    const Eigen::Vector3d centre = R_earlier_world * (T_world_later.translation() - T_world_earlier.translation());
    Eigen::Map<Eigen::Vector2d> residual(residuals);
    residual = across_ * centre;
    if (!jacobians) return true;
    // Twists in the camera frames (PoseManifold): the earlier one moves the centre by -v + centre x w,
    // the later one by R_earlier_later v.
    if (jacobians[0]) {
      Eigen::Map<Eigen::Matrix<double, 2, 7, Eigen::RowMajor>> J(jacobians[0]);
      J.leftCols<3>() = -across_;
      J.middleCols<3>(3) = across_ * skew(centre);
      J.col(6).setZero();
    }
    if (jacobians[1]) {
      Eigen::Map<Eigen::Matrix<double, 2, 7, Eigen::RowMajor>> J(jacobians[1]);
      J.leftCols<3>() = across_ * R_earlier_world * T_world_later.linear();
      J.rightCols<4>().setZero();
    }
    return true;
  }

 private:
  Eigen::Matrix<double, 2, 3> across_;  ///< the directions across the travel, scaled to residuals
};

/// ForwardMotionPrior between two keyframes of the window: the travel follows the expected chord
/// (the axis of travel turned by half their relative rotation) at the keyframes' present poses.
inline TravelDirectionFactor* forwardMotionFactor(const ForwardMotionOptions& options, const Eigen::Isometry3d& T_world_earlier,
                                                  const Eigen::Isometry3d& T_world_later) {
  const Eigen::Isometry3d T_earlier_later = T_world_earlier.inverse() * T_world_later;
  return new TravelDirectionFactor(options.chord(T_earlier_later.linear()), options.sigma_deg * M_PI / 180.0,
                                   T_earlier_later.translation().norm());
}

}  // namespace factors
}  // namespace semantic_edge_vo
