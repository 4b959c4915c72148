#include "semantic_edge_vo/frontend/forward_motion_prior.h"

#include <cmath>

namespace semantic_edge_vo {

Eigen::Vector3d ForwardMotionOptions::axis() const {
  const double pitch = pitch_deg * M_PI / 180.0, yaw = yaw_deg * M_PI / 180.0;
  return Eigen::Vector3d(std::sin(yaw) * std::cos(pitch), std::sin(pitch), std::cos(yaw) * std::cos(pitch));
}

Eigen::Vector3d ForwardMotionOptions::chord(const Eigen::Matrix3d& R_first_next) const {
  const Eigen::AngleAxisd rotation(R_first_next);
  return Eigen::AngleAxisd(0.5 * rotation.angle(), rotation.axis()) * axis();
}

ForwardMotionPrior::ForwardMotionPrior(const ForwardMotionOptions& options, double predicted_travel)
    : options_(options) {
  active_ = options.sigma_deg > 0.0 && predicted_travel > 0.0;
  if (!active_) return;
  const double sigma = options.sigma_deg * M_PI / 180.0;
  weight_ = 1.0 / (sigma * sigma * predicted_travel * predicted_travel);
}

double ForwardMotionPrior::evaluate(const Eigen::Isometry3d& T_cam_kf, Eigen::Matrix<double, 6, 6>* H, Vector6d* b) const {
  if (!active_) return 0.0;
  const Eigen::Matrix3d R_kf_cam = T_cam_kf.linear().transpose();
  const Eigen::Vector3d centre = -R_kf_cam * T_cam_kf.translation();  // frame's camera centre in the keyframe
  const Eigen::Vector3d chord = options_.chord(R_kf_cam);
  const Eigen::Vector3d e1 = chord.unitOrthogonal(), e2 = chord.cross(e1);
  double cost = 0.0;
  for (const Eigen::Vector3d& e : {e1, e2}) {
    const double r = e.dot(centre);
    cost += weight_ * r * r;
    if (!H) continue;
    // Left perturbation T <- exp(v, w) T moves the centre by -R_kf_cam v (rotation terms cancel).
    Vector6d J = Vector6d::Zero();
    J.head<3>() = -R_kf_cam.transpose() * e;
    H->noalias() += weight_ * J * J.transpose();
    b->noalias() += weight_ * r * J;
  }
  return cost;
}

}  // namespace semantic_edge_vo
