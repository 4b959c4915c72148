#pragma once
#include <ceres/sized_cost_function.h>

#include "semantic_edge_vo/camera.h"
#include "semantic_edge_vo/factors/pose_parameters.h"

namespace semantic_edge_vo {
namespace factors {

/// Point-to-tangent residual of a host edge point against its associated edge in a target keyframe
/// (the nearest edge of a shared class, found before the solve): n . (projection - match) / sigma,
/// px, with analytic derivatives. Parameters as PhotometricFactor.
class EdgeFactor : public ceres::SizedCostFunction<1, 7, 7, 1> {
 public:
  /// @param pair as PhotometricFactor's
  EdgeFactor(PosePairCache& pair, const Eigen::Vector3d& host_ray, const Eigen::Vector2d& match, const Eigen::Vector2d& normal,
             const PinholeCamera& camera, double sigma)
      : pair_(pair), host_ray_(host_ray), match_(match), normal_(normal), camera_(camera), sigma_(sigma) {}

  bool Evaluate(const double* const* parameters, double* residuals, double** jacobians) const override {
    const HostToTarget point(pair_.of(parameters[0], parameters[1]), parameters[2][0], host_ray_, jacobians != nullptr);
    if (point.P.z() <= 1e-6) return false;
    Eigen::Matrix<double, 2, 3> d_pixel;
    const Eigen::Vector2d pixel = project(point.P, camera_.fx, camera_.fy, camera_.cx, camera_.cy, &d_pixel);
    residuals[0] = normal_.dot(pixel - match_) / sigma_;
    if (jacobians) writeJacobians(point, normal_.transpose() * d_pixel / sigma_, jacobians);
    return true;
  }

 private:
  PosePairCache& pair_;
  Eigen::Vector3d host_ray_;
  Eigen::Vector2d match_, normal_;
  const PinholeCamera& camera_;
  double sigma_;
};

}  // namespace factors
}  // namespace semantic_edge_vo
