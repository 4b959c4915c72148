#pragma once
#include <Eigen/Geometry>

#include "semantic_edge_vo/common/se3.h"

namespace semantic_edge_vo {

using Matrix6d = Eigen::Matrix<double, 6, 6>;

// Pose covariances and velocities for the published odometry (docs/architecture.md, "Pose
// covariance and twist"). Twists and perturbations are (v, w), translation first, as in se3Exp.

/// Adjoint of T on twists: T * exp(xi) * T^-1 = exp(adjoint(T) * xi).
Matrix6d adjoint(const Eigen::Isometry3d& T);

/// Covariance of the Gauss-Newton solution of a least-squares problem: the inverse of its Hessian
/// (J^T W J), scaled by the residuals' reduced chi-square 2 * cost / (residuals - 6) and by
/// `correlated`, the number of residuals that carry one independent measurement. A direction the
/// residuals do not constrain gets a variance of `max_variance`.
Matrix6d solutionCovariance(const Matrix6d& hessian, double cost, int residuals, double correlated, double max_variance = 1e6);

/// The covariance of a pose tracked `travel` (translation, map units) from its keyframe, with the
/// uncertainty the tracking problem cannot see, which grows with that travel: errors of the
/// keyframe's depths and of the map's scale (docs/architecture.md, "Pose covariance and twist").
/// Adds a sigma of `scale_sigma` times the travel along it and of `travel_sigma` times the travel
/// along every axis (fractions) to the translation.
Matrix6d withTravelUncertainty(Matrix6d covariance, const Eigen::Vector3d& travel, double scale_sigma, double travel_sigma);

/// The frame tracker's covariance (of xi in T_cam_kf = exp(xi) * T_cam_kf, camera axes) as that of
/// base_link's pose in its own axes (zeta in T_odom_base * exp(zeta)), with base_link -> camera
/// `T_base_cam`.
Matrix6d baseCovariance(const Matrix6d& tracking, const Eigen::Isometry3d& T_base_cam);

/// A covariance in a body's axes, expressed in its parent's axes (nav_msgs/Odometry's pose
/// covariance is in header.frame_id's axes).
Matrix6d inParentAxes(const Matrix6d& body, const Eigen::Matrix3d& R_parent_body);

/// The velocity of a body, in its own axes at `T_now`, from its pose `dt` seconds before.
Vector6d bodyTwist(const Eigen::Isometry3d& T_before, const Eigen::Isometry3d& T_now, double dt);

}  // namespace semantic_edge_vo
