#pragma once
// Shared by the cost functions: a keyframe pose as one Ceres parameter block, and the projection of
// a host point into a target keyframe with its derivatives.
#include <array>

#include <ceres/manifold.h>
#include <Eigen/Geometry>

#include "semantic_edge_vo/common/se3.h"

namespace semantic_edge_vo {
namespace factors {

/// Camera-to-world pose as 7 parameters: translation (3), then rotation as a quaternion (x, y, z, w).
using PoseParameters = std::array<double, 7>;
PoseParameters toParameters(const Eigen::Isometry3d& T_world_cam);
Eigen::Isometry3d fromParameters(const double* parameters);

/// Poses change by a twist in the camera frame, T <- T exp(v, w), 6 tangent dimensions: rotations
/// turn about the camera's own centre (a twist in the world frame would swing a camera hundreds of
/// metres from the origin about it, coupling rotation and translation badly). The cost functions
/// give their Jacobians in the tangent space, padded with a zero column to the 7 parameters;
/// PlusJacobian is therefore [I; 0], so Ceres' product of the two is the tangent Jacobian.
class PoseManifold : public ceres::Manifold {
 public:
  int AmbientSize() const override { return 7; }
  int TangentSize() const override { return 6; }
  bool Plus(const double* x, const double* delta, double* x_plus_delta) const override;
  bool PlusJacobian(const double* x, double* jacobian) const override;
  bool Minus(const double* y, const double* x, double* y_minus_x) const override;
  bool MinusJacobian(const double* x, double* jacobian) const override;
};

/// The relative pose of a (host, target) keyframe pair.
struct PairTransform {
  Eigen::Matrix3d R_target_host;
  Eigen::Vector3d t_target_host;  ///< host centre in the target frame: R_target_world (t_host - t_target)
};
PairTransform pairTransform(const double* host, const double* target);

/// The point at a host ray (pixel on the z = 1 plane) and inverse depth rho, seen from the target,
/// scaled by rho (homogeneous: finite at rho = 0), with its derivatives when asked for.
struct HostToTarget {
  Eigen::Vector3d P;                    ///< in the target optical frame, times rho
  Eigen::Matrix<double, 3, 6> d_host;   ///< dP / d(host twist)
  Eigen::Matrix<double, 3, 6> d_target; ///< dP / d(target twist)
  Eigen::Vector3d d_rho;                ///< dP / d rho

  /// @param with_derivatives false: only P (Ceres evaluates many residuals without Jacobians)
  HostToTarget(const PairTransform& pair, double rho, const Eigen::Vector3d& host_ray, bool with_derivatives);
};

/// Pixel of a (scaled) camera point and its derivative.
inline Eigen::Vector2d project(const Eigen::Vector3d& P, double fx, double fy, double cx, double cy,
                               Eigen::Matrix<double, 2, 3>* d_point) {
  const double iz = 1.0 / P.z();
  *d_point << fx * iz, 0.0, -fx * P.x() * iz * iz, 0.0, fy * iz, -fy * P.y() * iz * iz;
  return Eigen::Vector2d(fx * P.x() * iz + cx, fy * P.y() * iz + cy);
}

}  // namespace factors
}  // namespace semantic_edge_vo
