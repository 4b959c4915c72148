#include "semantic_edge_vo/backend/factors/pose_parameters.h"

#include <algorithm>

namespace semantic_edge_vo {
namespace factors {

PoseParameters toParameters(const Eigen::Isometry3d& T_world_cam) {
  const Eigen::Quaterniond q(T_world_cam.linear());
  const Eigen::Vector3d& t = T_world_cam.translation();
  return {t.x(), t.y(), t.z(), q.x(), q.y(), q.z(), q.w()};
}

Eigen::Isometry3d fromParameters(const double* parameters) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::Quaterniond(parameters[6], parameters[3], parameters[4], parameters[5]).normalized().toRotationMatrix();
  T.translation() = Eigen::Vector3d(parameters[0], parameters[1], parameters[2]);
  return T;
}

bool PoseManifold::Plus(const double* x, const double* delta, double* x_plus_delta) const {
  const PoseParameters moved = toParameters(fromParameters(x) * se3Exp(Eigen::Map<const Vector6d>(delta)));
  std::copy(moved.begin(), moved.end(), x_plus_delta);
  return true;
}

bool PoseManifold::PlusJacobian(const double*, double* jacobian) const {
  Eigen::Map<Eigen::Matrix<double, 7, 6, Eigen::RowMajor>> J(jacobian);
  J.setZero();
  J.topRows<6>().setIdentity();
  return true;
}

bool PoseManifold::Minus(const double* y, const double* x, double* y_minus_x) const {
  Eigen::Map<Vector6d> difference(y_minus_x);
  difference = se3Log(fromParameters(x).inverse() * fromParameters(y));
  return true;
}

bool PoseManifold::MinusJacobian(const double*, double* jacobian) const {
  Eigen::Map<Eigen::Matrix<double, 6, 7, Eigen::RowMajor>> J(jacobian);
  J.setZero();
  J.leftCols<6>().setIdentity();
  return true;
}

PairTransform pairTransform(const double* host, const double* target) {
  const Eigen::Isometry3d T_world_host = fromParameters(host), T_world_target = fromParameters(target);
  const Eigen::Matrix3d R_target_world = T_world_target.linear().transpose();
  return {R_target_world * T_world_host.linear(), R_target_world * (T_world_host.translation() - T_world_target.translation())};
}

HostToTarget::HostToTarget(const PairTransform& pair, double rho, const Eigen::Vector3d& host_ray, bool with_derivatives) {
  // Homogeneous in rho: the point times rho.
  P = pair.R_target_host * host_ray + rho * pair.t_target_host;
  if (!with_derivatives) return;
  // A host twist moves the point by v + w x X in the host frame (times rho: rho v + w x ray).
  d_host.leftCols<3>() = rho * pair.R_target_host;
  d_host.rightCols<3>() = -pair.R_target_host * skew(host_ray);
  // A target twist moves it by -(v + w x X) in the target frame.
  d_target.leftCols<3>() = -rho * Eigen::Matrix3d::Identity();
  d_target.rightCols<3>() = skew(P);
  d_rho = pair.t_target_host;
}

}  // namespace factors
}  // namespace semantic_edge_vo
