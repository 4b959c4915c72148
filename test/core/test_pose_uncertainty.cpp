#include <random>

#include <gtest/gtest.h>

#include "semantic_edge_vo/common/pose_uncertainty.h"

namespace semantic_edge_vo {
namespace {

Vector6d sample(std::mt19937* random, const Matrix6d& covariance) {
  const Eigen::LLT<Matrix6d> llt(covariance);
  std::normal_distribution<double> normal;
  Vector6d z;
  for (int i = 0; i < 6; ++i) z(i) = normal(*random);
  return llt.matrixL() * z;
}

Eigen::Isometry3d somePose() {
  Vector6d xi;
  xi << 0.3, -1.2, 2.0, 0.2, -0.4, 0.9;
  return se3Exp(xi);
}

TEST(PoseUncertainty, AdjointMovesAPerturbationAcrossAPose) {
  const Eigen::Isometry3d T = somePose();
  Vector6d xi;
  xi << 0.01, 0.02, -0.03, 0.004, -0.002, 0.003;
  const Eigen::Isometry3d lhs = T * se3Exp(xi) * T.inverse();
  const Eigen::Isometry3d rhs = se3Exp(adjoint(T) * xi);
  EXPECT_LT((lhs.matrix() - rhs.matrix()).norm(), 1e-12);
}

TEST(PoseUncertainty, SolutionCovarianceMatchesTheSpreadOfLeastSquaresEstimates) {
  // A linear problem y = A x + noise (sigma 0.5), weighted with a wrong sigma (1): the reduced
  // chi-square rescales the inverse Hessian to the estimates' real spread.
  std::mt19937 random(7);
  std::normal_distribution<double> noise(0.0, 0.5);
  const int n = 200;
  Eigen::MatrixXd A = Eigen::MatrixXd::Random(n, 6);
  const Vector6d x_true = Vector6d::LinSpaced(6, -1.0, 1.0);
  const Matrix6d H = A.transpose() * A;
  Matrix6d predicted = Matrix6d::Zero(), spread = Matrix6d::Zero();
  const int trials = 3000;
  for (int t = 0; t < trials; ++t) {
    Eigen::VectorXd y = A * x_true;
    for (int i = 0; i < n; ++i) y(i) += noise(random);
    const Vector6d x = H.ldlt().solve(A.transpose() * y);
    const double cost = 0.5 * (A * x - y).squaredNorm();
    predicted += solutionCovariance(H, cost, n, 1.0) / trials;
    spread += (x - x_true) * (x - x_true).transpose() / trials;
  }
  for (int i = 0; i < 6; ++i) EXPECT_NEAR(predicted(i, i), spread(i, i), 0.1 * spread(i, i)) << "variance " << i;
}

TEST(PoseUncertainty, AnUnconstrainedDirectionIsUnknownNotInfinite) {
  Matrix6d H = Matrix6d::Identity();
  H(5, 5) = 0.0;  // nothing constrains the yaw
  const Matrix6d covariance = solutionCovariance(H, 97.0, 200, 1.0, 1e6);
  EXPECT_NEAR(covariance(0, 0), 1.0, 1e-9);
  EXPECT_NEAR(covariance(5, 5), 1e6, 1.0);
}

TEST(PoseUncertainty, TravelFromTheKeyframeWidensTheTranslationOnly) {
  const Matrix6d tracked = 1e-6 * Matrix6d::Identity();
  const Eigen::Vector3d travel(0.0, 0.0, 2.0);  // 2 m ahead
  const Matrix6d covariance = withTravelUncertainty(tracked, travel, 0.02, 0.01);
  EXPECT_NEAR(covariance(2, 2), 1e-6 + 0.04 * 0.04 + 0.02 * 0.02, 1e-12);  // along the travel: scale and travel
  EXPECT_NEAR(covariance(0, 0), 1e-6 + 0.02 * 0.02, 1e-12);                // across it: travel only
  EXPECT_NEAR(covariance(1, 1), 1e-6 + 0.02 * 0.02, 1e-12);
  const Eigen::Matrix3d rotation = covariance.bottomRightCorner<3, 3>(), cross = covariance.topRightCorner<3, 3>();
  EXPECT_TRUE(rotation.isApprox(tracked.bottomRightCorner<3, 3>()));
  EXPECT_TRUE(cross.isZero());
  EXPECT_TRUE(withTravelUncertainty(tracked, Eigen::Vector3d::Zero(), 0.02, 0.01).isApprox(tracked));
}

TEST(PoseUncertainty, BaseCovarianceIsTheSpreadOfBaseLinkUnderTrackingErrors) {
  // Sampled tracking errors exp(xi) * T_cam_kf move base_link by T_odom_base^-1 * T_odom_base':
  // their spread is baseCovariance.
  std::mt19937 random(3);
  Matrix6d tracking = Matrix6d::Zero();
  tracking.diagonal() << 4e-4, 1e-4, 9e-4, 1e-6, 4e-6, 1e-6;
  tracking(0, 4) = tracking(4, 0) = 1e-5;
  Eigen::Isometry3d T_base_cam = Eigen::Isometry3d::Identity();
  T_base_cam.linear() << 0, 0, 1, -1, 0, 0, 0, -1, 0;
  T_base_cam.translation() << 1.5, 0.2, 1.65;
  const Eigen::Isometry3d T_world_kf = somePose(), T_cam_kf = se3Exp(Vector6d::Constant(0.05));
  const auto base_of = [&](const Eigen::Isometry3d& cam_kf) { return T_base_cam * (T_world_kf * cam_kf.inverse()) * T_base_cam.inverse(); };
  const Eigen::Isometry3d T_odom_base = base_of(T_cam_kf);
  Matrix6d spread = Matrix6d::Zero();
  const int trials = 20000;
  for (int t = 0; t < trials; ++t) {
    const Vector6d zeta = se3Log(T_odom_base.inverse() * base_of(se3Exp(sample(&random, tracking)) * T_cam_kf));
    spread += zeta * zeta.transpose() / trials;
  }
  const Matrix6d predicted = baseCovariance(tracking, T_base_cam);
  EXPECT_LT((predicted - spread).norm(), 0.05 * predicted.norm()) << "predicted\n" << predicted << "\nspread\n" << spread;
}

TEST(PoseUncertainty, InParentAxesRotatesBothBlocks) {
  Matrix6d body = Matrix6d::Zero();
  body.diagonal() << 1, 2, 3, 4, 5, 6;
  const Eigen::Matrix3d yaw90 = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const Matrix6d parent = inParentAxes(body, yaw90);  // body x is the parent's y
  EXPECT_NEAR(parent(0, 0), 2.0, 1e-12);
  EXPECT_NEAR(parent(1, 1), 1.0, 1e-12);
  EXPECT_NEAR(parent(3, 3), 5.0, 1e-12);
  EXPECT_NEAR(parent(4, 4), 4.0, 1e-12);
  EXPECT_NEAR(parent(5, 5), 6.0, 1e-12);
}

TEST(PoseUncertainty, BodyTwistOfACarTurningLeft) {
  // 10 m/s forward (base x) while yawing left at 0.2 rad/s, 0.1 s apart.
  const Eigen::Isometry3d before = somePose();
  Vector6d motion;
  motion << 1.0, 0.0, 0.0, 0.0, 0.0, 0.02;
  const Vector6d twist = bodyTwist(before, before * se3Exp(motion), 0.1);
  EXPECT_NEAR(twist(0), 10.0, 0.02);
  EXPECT_NEAR(twist(1), 0.0, 0.15);  // the chord of the arc points half the turn to the left
  EXPECT_NEAR(twist(5), 0.2, 1e-9);
  EXPECT_NEAR(twist.segment<2>(3).norm(), 0.0, 1e-9);
}

}  // namespace
}  // namespace semantic_edge_vo
