#pragma once
#include <ceres/ceres.h>

#include "semantic_edge_vo/factors/pose_parameters.h"

namespace semantic_edge_vo {
namespace factors {

/// Point-to-tangent residual of a host edge point against its associated edge in a target keyframe
/// (the nearest edge of a shared class, found before the solve): n . (projection - match) / sigma,
/// px. Parameters as PhotometricFactor.
class EdgeFactor {
 public:
  EdgeFactor(const Eigen::Vector3d& host_ray, const Eigen::Vector2d& match, const Eigen::Vector2d& normal,
             double fx, double fy, double cx, double cy, double sigma)
      : host_ray_(host_ray), match_(match), normal_(normal), fx_(fx), fy_(fy), cx_(cx), cy_(cy), sigma_(sigma) {}

  template <typename T>
  bool operator()(const T* q_h, const T* t_h, const T* q_t, const T* t_t, const T* rho, T* residual) const {
    const Eigen::Matrix<T, 3, 1> p = hostToTarget(q_h, t_h, q_t, t_t, rho[0], host_ray_);
    if (p.z() <= T(1e-6)) return false;
    const T du = fx_ * p.x() / p.z() + cx_ - match_.x(), dv = fy_ * p.y() / p.z() + cy_ - match_.y();
    residual[0] = (normal_.x() * du + normal_.y() * dv) / sigma_;
    return true;
  }

  static ceres::CostFunction* Create(const Eigen::Vector3d& host_ray, const Eigen::Vector2d& match, const Eigen::Vector2d& normal,
                                     double fx, double fy, double cx, double cy, double sigma) {
    return new ceres::AutoDiffCostFunction<EdgeFactor, 1, 4, 3, 4, 3, 1>(
        new EdgeFactor(host_ray, match, normal, fx, fy, cx, cy, sigma));
  }

 private:
  Eigen::Vector3d host_ray_;
  Eigen::Vector2d match_, normal_;
  double fx_, fy_, cx_, cy_, sigma_;
};

}  // namespace factors
}  // namespace semantic_edge_vo
