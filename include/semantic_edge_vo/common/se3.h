#pragma once
#include <Eigen/Geometry>

namespace semantic_edge_vo {

using Vector6d = Eigen::Matrix<double, 6, 1>;

/// Skew-symmetric matrix: skew(a) * b = a x b.
inline Eigen::Matrix3d skew(const Eigen::Vector3d& a) {
  Eigen::Matrix3d m;
  m << 0, -a.z(), a.y(), a.z(), 0, -a.x(), -a.y(), a.x(), 0;
  return m;
}

/// The pose as part of a map scaled by `scale` about the point `about`: its position moves, its
/// orientation stays.
inline void scaleAbout(double scale, const Eigen::Vector3d& about, Eigen::Isometry3d* pose) {
  pose->translation() = about + scale * (pose->translation() - about);
}

/// The same pose with its rotation made exactly orthonormal again (long products drift).
Eigen::Isometry3d orthonormalized(const Eigen::Isometry3d& pose);

/// SO(3) exponential: the rotation by |w| radians about w.
Eigen::Matrix3d so3Exp(const Eigen::Vector3d& w);
/// SE(3) exponential of a twist (v, w): translation part first, rotation part last.
Eigen::Isometry3d se3Exp(const Vector6d& twist);
/// Inverse of se3Exp (rotation angle below pi).
Vector6d se3Log(const Eigen::Isometry3d& pose);

}  // namespace semantic_edge_vo
