#include "semantic_edge_vo/common/se3.h"

#include <cmath>

namespace semantic_edge_vo {
namespace {

/// Left Jacobian of SO(3), V in exp((v, w)) = (exp(w), V v).
Eigen::Matrix3d leftJacobian(const Eigen::Vector3d& w) {
  const double theta = w.norm();
  const Eigen::Matrix3d W = skew(w);
  if (theta < 1e-8) return Eigen::Matrix3d::Identity() + 0.5 * W;
  const double t2 = theta * theta;
  return Eigen::Matrix3d::Identity() + (1.0 - std::cos(theta)) / t2 * W + (theta - std::sin(theta)) / (t2 * theta) * W * W;
}

}  // namespace

Eigen::Isometry3d orthonormalized(const Eigen::Isometry3d& pose) {
  Eigen::Isometry3d result = pose;
  result.linear() = Eigen::Quaterniond(pose.linear()).normalized().toRotationMatrix();
  return result;
}

Eigen::Matrix3d so3Exp(const Eigen::Vector3d& w) {
  const double theta = w.norm();
  return theta < 1e-12 ? Eigen::Matrix3d::Identity() : Eigen::AngleAxisd(theta, w / theta).toRotationMatrix();
}

Eigen::Isometry3d se3Exp(const Vector6d& twist) {
  const Eigen::Vector3d v = twist.head<3>(), w = twist.tail<3>();
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = so3Exp(w);
  pose.translation() = leftJacobian(w) * v;
  return pose;
}

Vector6d se3Log(const Eigen::Isometry3d& pose) {
  const Eigen::AngleAxisd angle_axis(pose.linear());
  const Eigen::Vector3d w = angle_axis.angle() * angle_axis.axis();
  Vector6d twist;
  twist.head<3>() = leftJacobian(w).inverse() * pose.translation();
  twist.tail<3>() = w;
  return twist;
}

}  // namespace semantic_edge_vo
