#pragma once
#include <ceres/ceres.h>
#include <ceres/cubic_interpolation.h>

#include "semantic_edge_vo/factors/pose_parameters.h"

namespace semantic_edge_vo {
namespace factors {

using Interpolator = ceres::BiCubicInterpolator<ceres::Grid2D<float, 1>>;

/// Photometric residual of a host point in a target keyframe: gradient magnitude of the target at
/// the projection minus the host's value (paper III-C), divided by sigma. Parameters: host rotation
/// (4) and translation (3), target rotation (4) and translation (3), inverse depth (1).
class PhotometricFactor {
 public:
  PhotometricFactor(const Eigen::Vector3d& host_ray, double host_value, const Interpolator* target,
                    double fx, double fy, double cx, double cy, double sigma)
      : host_ray_(host_ray), host_value_(host_value), target_(target), fx_(fx), fy_(fy), cx_(cx), cy_(cy), sigma_(sigma) {}

  template <typename T>
  bool operator()(const T* q_h, const T* t_h, const T* q_t, const T* t_t, const T* rho, T* residual) const {
    const Eigen::Matrix<T, 3, 1> p = hostToTarget(q_h, t_h, q_t, t_t, rho[0], host_ray_);
    if (p.z() <= T(1e-6)) return false;
    const T u = fx_ * p.x() / p.z() + cx_, v = fy_ * p.y() / p.z() + cy_;
    T value;
    target_->Evaluate(v, u, &value);  // row, column
    residual[0] = (value - host_value_) / sigma_;
    return true;
  }

  static ceres::CostFunction* Create(const Eigen::Vector3d& host_ray, double host_value, const Interpolator* target,
                                     double fx, double fy, double cx, double cy, double sigma) {
    return new ceres::AutoDiffCostFunction<PhotometricFactor, 1, 4, 3, 4, 3, 1>(
        new PhotometricFactor(host_ray, host_value, target, fx, fy, cx, cy, sigma));
  }

 private:
  Eigen::Vector3d host_ray_;
  double host_value_;
  const Interpolator* target_;
  double fx_, fy_, cx_, cy_, sigma_;
};

}  // namespace factors
}  // namespace semantic_edge_vo
