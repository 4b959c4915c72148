#pragma once
#include <ceres/cubic_interpolation.h>
#include <ceres/sized_cost_function.h>

#include "semantic_edge_vo/camera.h"
#include "semantic_edge_vo/factors/pose_parameters.h"

namespace semantic_edge_vo {
namespace factors {

using Interpolator = ceres::BiCubicInterpolator<ceres::Grid2D<float, 1>>;

/// Photometric residual of a host point in a target keyframe: gradient magnitude of the target at
/// the projection minus the host's value (paper III-C), divided by sigma. Bicubic samples with their
/// exact derivatives (beyond the border the image continues flat, so a step that pushes a point out
/// is not a failure), analytic Jacobians. Parameters: host pose (7), target pose (7), inverse depth (1).
class PhotometricFactor : public ceres::SizedCostFunction<1, 7, 7, 1> {
 public:
  /// @param pair shared by the factors of one (host, target) pair, outlives them
  PhotometricFactor(PosePairCache& pair, const Eigen::Vector3d& host_ray, double host_value, const Interpolator& target,
                    const PinholeCamera& camera, double sigma)
      : pair_(pair), host_ray_(host_ray), host_value_(host_value), target_(target), camera_(camera), sigma_(sigma) {}

  bool Evaluate(const double* const* parameters, double* residuals, double** jacobians) const override {
    const HostToTarget point(pair_.of(parameters[0], parameters[1]), parameters[2][0], host_ray_, jacobians != nullptr);
    if (point.P.z() <= 1e-6) return false;
    Eigen::Matrix<double, 2, 3> d_pixel;
    const Eigen::Vector2d pixel = project(point.P, camera_.fx, camera_.fy, camera_.cx, camera_.cy, &d_pixel);
    double value = 0.0, d_row = 0.0, d_column = 0.0;
    target_.Evaluate(pixel.y(), pixel.x(), &value, &d_row, &d_column);
    residuals[0] = (value - host_value_) / sigma_;
    if (!jacobians) return true;
    writeJacobians(point, Eigen::RowVector2d(d_column, d_row) * d_pixel / sigma_, jacobians);
    return true;
  }

 private:
  PosePairCache& pair_;
  Eigen::Vector3d host_ray_;
  double host_value_;
  const Interpolator& target_;
  const PinholeCamera& camera_;
  double sigma_;
};

}  // namespace factors
}  // namespace semantic_edge_vo
