#pragma once
#include <ceres/sized_cost_function.h>

#include "semantic_edge_vo/factors/pose_parameters.h"

namespace semantic_edge_vo {
namespace factors {

/// Point-to-tangent residual of a host edge point against its associated edge in a target keyframe
/// (the nearest edge of a shared class, found before the solve): n . (projection - match) / sigma,
/// px, with analytic derivatives. Parameters as PhotometricFactor.
class EdgeFactor : public ceres::SizedCostFunction<1, 7, 7, 1> {
 public:
  EdgeFactor(const Eigen::Vector3d& host_ray, const Eigen::Vector2d& match, const Eigen::Vector2d& normal,
             double fx, double fy, double cx, double cy, double sigma)
      : host_ray_(host_ray), match_(match), normal_(normal), fx_(fx), fy_(fy), cx_(cx), cy_(cy), sigma_(sigma) {}

  bool Evaluate(const double* const* parameters, double* residuals, double** jacobians) const override {
    const HostToTarget point(parameters[0], parameters[1], parameters[2][0], host_ray_);
    if (point.P.z() <= 1e-6) return false;
    Eigen::Matrix<double, 2, 3> d_pixel;
    const Eigen::Vector2d pixel = project(point.P, fx_, fy_, cx_, cy_, &d_pixel);
    residuals[0] = normal_.dot(pixel - match_) / sigma_;
    if (!jacobians) return true;
    const Eigen::RowVector3d d_point = normal_.transpose() * d_pixel / sigma_;
    writePoseJacobian(d_point * point.d_host, jacobians[0]);
    writePoseJacobian(d_point * point.d_target, jacobians[1]);
    if (jacobians[2]) jacobians[2][0] = d_point.dot(point.d_rho);
    return true;
  }

 private:
  Eigen::Vector3d host_ray_;
  Eigen::Vector2d match_, normal_;
  double fx_, fy_, cx_, cy_, sigma_;
};

}  // namespace factors
}  // namespace semantic_edge_vo
