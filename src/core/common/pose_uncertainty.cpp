#include "semantic_edge_vo/common/pose_uncertainty.h"

#include <algorithm>

#include <Eigen/Eigenvalues>

namespace semantic_edge_vo {

Matrix6d adjoint(const Eigen::Isometry3d& T) {
  const Eigen::Matrix3d R = T.linear();
  Matrix6d result = Matrix6d::Zero();
  result.topLeftCorner<3, 3>() = R;
  result.topRightCorner<3, 3>() = skew(T.translation()) * R;
  result.bottomRightCorner<3, 3>() = R;
  return result;
}

Matrix6d solutionCovariance(const Matrix6d& hessian, double cost, int residuals, double correlated, double max_variance) {
  const double reduced_chi2 = 2.0 * cost / std::max(1, residuals - 6);
  const double scale = std::max(1e-12, correlated * reduced_chi2);
  const Eigen::SelfAdjointEigenSolver<Matrix6d> eigen(0.5 * (hessian + hessian.transpose()));
  const Vector6d inverse = (eigen.eigenvalues().array().max(scale / max_variance)).inverse();
  return scale * eigen.eigenvectors() * inverse.asDiagonal() * eigen.eigenvectors().transpose();
}

Matrix6d withTravelUncertainty(Matrix6d covariance, const Eigen::Vector3d& travel, double scale_sigma, double travel_sigma) {
  covariance.topLeftCorner<3, 3>() += scale_sigma * scale_sigma * travel * travel.transpose() +
                                      travel_sigma * travel_sigma * travel.squaredNorm() * Eigen::Matrix3d::Identity();
  return covariance;
}

Matrix6d baseCovariance(const Matrix6d& tracking, const Eigen::Isometry3d& T_base_cam) {
  // T_world_cam = T_world_kf * T_cam_kf^-1: a perturbation exp(xi) on the left of T_cam_kf is
  // exp(-xi) on the right of T_world_cam, and T_odom_base = T_base_cam * T_world_cam * T_base_cam^-1
  // moves by exp(-adjoint(T_base_cam) * xi) on its right. The sign does not change a covariance.
  const Matrix6d A = adjoint(T_base_cam);
  return A * tracking * A.transpose();
}

Matrix6d inParentAxes(const Matrix6d& body, const Eigen::Matrix3d& R_parent_body) {
  Matrix6d R = Matrix6d::Zero();
  R.topLeftCorner<3, 3>() = R_parent_body;
  R.bottomRightCorner<3, 3>() = R_parent_body;
  return R * body * R.transpose();
}

Vector6d bodyTwist(const Eigen::Isometry3d& T_before, const Eigen::Isometry3d& T_now, double dt) {
  Vector6d twist;
  twist.head<3>() = T_now.linear().transpose() * (T_now.translation() - T_before.translation()) / dt;
  // The axis of the relative rotation is the same in both poses' axes.
  const Eigen::AngleAxisd rotation(T_before.linear().transpose() * T_now.linear());
  twist.tail<3>() = rotation.angle() * rotation.axis() / dt;
  return twist;
}

}  // namespace semantic_edge_vo
