#include <gtest/gtest.h>

#include "semantic_edge_vo/frontend/forward_motion_prior.h"

namespace semantic_edge_vo {
namespace {

/// T_cam_kf of a frame whose camera centre is at `centre` in the keyframe, turned by `yaw` rad.
Eigen::Isometry3d frameAt(const Eigen::Vector3d& centre, double yaw) {
  Eigen::Isometry3d T_kf_cam = Eigen::Isometry3d::Identity();
  T_kf_cam.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitY()).toRotationMatrix();
  T_kf_cam.translation() = centre;
  return T_kf_cam.inverse();
}

TEST(ForwardMotionPrior, IsFreeAlongTheChordAndCostsSideways) {
  ForwardMotionOptions options;
  options.sigma_deg = 2.0;
  const ForwardMotionPrior prior(options, 1.0);
  ASSERT_TRUE(prior.active());
  EXPECT_NEAR(prior.evaluate(frameAt(Eigen::Vector3d(0, 0, 1), 0.0), nullptr, nullptr), 0.0, 1e-12);
  // On a curve the chord bisects the heading change: turning right by 0.1 rad, the chord points
  // 0.05 rad to the right (optical x).
  const double yaw = 0.1;
  EXPECT_NEAR(prior.evaluate(frameAt(Eigen::Vector3d(std::sin(yaw / 2), 0, std::cos(yaw / 2)), yaw), nullptr, nullptr), 0.0, 1e-12);
  // One sigma sideways costs 1.
  const double sigma = 2.0 * M_PI / 180.0;
  EXPECT_NEAR(prior.evaluate(frameAt(Eigen::Vector3d(std::sin(sigma), 0, std::cos(sigma)), 0.0), nullptr, nullptr), 1.0, 0.01);
  ForwardMotionOptions off;
  off.sigma_deg = 0.0;
  EXPECT_FALSE(ForwardMotionPrior(off, 1.0).active());  // sigma 0: off
  EXPECT_FALSE(ForwardMotionPrior(options, 0.0).active());                 // no motion model yet
}

TEST(ForwardMotionPrior, GradientMatchesCentralDifferences) {
  ForwardMotionOptions options;
  options.sigma_deg = 3.0;
  options.pitch_deg = -1.2;
  const ForwardMotionPrior prior(options, 0.8);
  const Eigen::Isometry3d T = frameAt(Eigen::Vector3d(0.1, 0.03, 0.8), 0.02);
  Eigen::Matrix<double, 6, 6> H = Eigen::Matrix<double, 6, 6>::Zero();
  Vector6d b = Vector6d::Zero();
  prior.evaluate(T, &H, &b);
  // b is half the cost's gradient in the translation part (Gauss-Newton: cost = sum w r^2).
  for (int i = 0; i < 3; ++i) {
    Vector6d delta = Vector6d::Zero();
    delta(i) = 1e-6;
    const double numeric = (prior.evaluate(se3Exp(delta) * T, nullptr, nullptr) - prior.evaluate(se3Exp(-delta) * T, nullptr, nullptr)) / 2e-6;
    EXPECT_NEAR(2.0 * b(i), numeric, 1e-3 * (1.0 + std::abs(numeric))) << i;
  }
  const double trace = H.topLeftCorner<3, 3>().trace();
  EXPECT_GT(trace, 0.0);
}

}  // namespace
}  // namespace semantic_edge_vo
