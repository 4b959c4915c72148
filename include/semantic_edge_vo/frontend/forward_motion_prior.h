#pragma once
#include <Eigen/Geometry>

#include "semantic_edge_vo/common/se3.h"

namespace semantic_edge_vo {

/// The direction a vehicle-mounted camera travels in, in its optical frame, and how firmly it holds.
struct ForwardMotionOptions {
  double sigma_deg = 5.0;  ///< 0: off. Sigma of the angle between the travel and the axis, degrees
  double pitch_deg = 0.0;  ///< axis of travel: positive points down in the image (optical y)
  double yaw_deg = 0.0;    ///< positive points right (optical x)

  /// The unit axis of travel in the camera's optical frame.
  Eigen::Vector3d axis() const;
  /// Expected direction of the chord from one pose to the next, in the first one's optical frame:
  /// the axis turned by half the rotation between them (on a curve the chord bisects the heading change).
  Eigen::Vector3d chord(const Eigen::Matrix3d& R_first_next) const;
};

/// A car's camera moves along its forward axis (no side slip; on a curve, the chord between two
/// poses bisects the heading change). Edges and forward motion leave the lateral and vertical
/// direction of travel nearly unobservable: a shifted focus of expansion plus depths re-triangulated
/// from it explain edge flow equally well, and the error feeds back through every new keyframe.
/// This soft prior pins the direction. Residuals: the components of the frame's camera centre in
/// the keyframe orthogonal to the expected chord, divided by the travel the motion model predicts
/// (a constant, so the residuals are linear in the centre) and by sigma.
class ForwardMotionPrior {
 public:
  /// @param predicted_travel distance the constant-velocity guess travels (map units); the prior is
  ///        inactive when it is not positive (no motion model yet) or the options are off
  ForwardMotionPrior(const ForwardMotionOptions& options, double predicted_travel);

  bool active() const { return active_; }
  /// Cost at T_cam_kf (frame <- keyframe); adds the Gauss-Newton terms of a left se(3) perturbation
  /// of T_cam_kf to H and b when they are given.
  double evaluate(const Eigen::Isometry3d& T_cam_kf, Eigen::Matrix<double, 6, 6>* H, Vector6d* b) const;

 private:
  ForwardMotionOptions options_;
  double weight_ = 0.0;  ///< 1 / (sigma^2 travel^2)
  bool active_ = false;
};

}  // namespace semantic_edge_vo
