// The window optimiser's analytic Jacobians against central differences through the pose manifold.
#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "semantic_edge_vo/factors/edge_factor.h"
#include "semantic_edge_vo/factors/relative_rotation_factor.h"
#include "semantic_edge_vo/factors/travel_direction_factor.h"
#include "semantic_edge_vo/factors/photometric_factor.h"
#include "semantic_edge_vo/image_pyramid.h"

namespace semantic_edge_vo {
namespace {

using factors::PoseParameters;

/// Residual and Jacobians of a 1-residual factor over (host pose, target pose, inverse depth); the
/// numeric ones perturb the poses through PoseManifold::Plus, like the solver.
struct Derivatives {
  Eigen::Matrix<double, 1, 6> host, target;
  double rho = 0.0;
};

Derivatives analytic(const ceres::CostFunction& factor, PoseParameters host, PoseParameters target, double rho) {
  const double* parameters[] = {host.data(), target.data(), &rho};
  double residual = 0.0;
  Eigen::Matrix<double, 1, 7> j_host, j_target;
  double j_rho = 0.0;
  double* jacobians[] = {j_host.data(), j_target.data(), &j_rho};
  EXPECT_TRUE(factor.Evaluate(parameters, &residual, jacobians));
  EXPECT_EQ(j_host(6), 0.0);
  EXPECT_EQ(j_target(6), 0.0);
  return {j_host.head<6>(), j_target.head<6>(), j_rho};
}

Derivatives numeric(const ceres::CostFunction& factor, const PoseParameters& host, const PoseParameters& target, double rho,
                    double step) {
  const auto residual = [&](const PoseParameters& h, const PoseParameters& t, double r) {
    const double* parameters[] = {h.data(), t.data(), &r};
    double value = 0.0;
    EXPECT_TRUE(factor.Evaluate(parameters, &value, nullptr));
    return value;
  };
  const factors::PoseManifold manifold;
  Derivatives result;
  for (int i = 0; i < 6; ++i) {
    Vector6d delta = Vector6d::Zero();
    delta(i) = step;
    PoseParameters plus, minus;
    manifold.Plus(host.data(), delta.data(), plus.data());
    manifold.Plus(host.data(), (-delta).eval().data(), minus.data());
    result.host(i) = (residual(plus, target, rho) - residual(minus, target, rho)) / (2 * step);
    manifold.Plus(target.data(), delta.data(), plus.data());
    manifold.Plus(target.data(), (-delta).eval().data(), minus.data());
    result.target(i) = (residual(host, plus, rho) - residual(host, minus, rho)) / (2 * step);
  }
  const double rho_step = step * rho;
  result.rho = (residual(host, target, rho + rho_step) - residual(host, target, rho - rho_step)) / (2 * rho_step);
  return result;
}

void expectNear(const Derivatives& a, const Derivatives& b, double tolerance) {
  for (int i = 0; i < 6; ++i) {
    EXPECT_NEAR(a.host(i), b.host(i), tolerance * (1.0 + std::abs(b.host(i)))) << "host " << i;
    EXPECT_NEAR(a.target(i), b.target(i), tolerance * (1.0 + std::abs(b.target(i)))) << "target " << i;
  }
  EXPECT_NEAR(a.rho, b.rho, tolerance * (1.0 + std::abs(b.rho)));
}

PinholeCamera testCamera() {
  PinholeCamera camera = kittiCamera();
  camera.width = 640;
  camera.height = 360;
  camera.cx = 320.0;
  camera.cy = 180.0;
  return camera;
}

/// Two keyframes 0.8 m apart with a small turn, and a host point 12 m ahead; `host_turn` (rad)
/// turns both cameras in the world (a world-frame vs camera-frame twist mix-up shows then).
struct Scene {
  PoseParameters host, target;
  Eigen::Vector3d ray;
  double rho = 1.0 / 12.0;

  explicit Scene(double host_turn = 0.0) {
    Eigen::Isometry3d T_host = Eigen::Isometry3d::Identity();
    T_host.linear() = Eigen::AngleAxisd(host_turn, Eigen::Vector3d(0.3, 1.0, -0.2).normalized()).toRotationMatrix();
    T_host.translation() = Eigen::Vector3d(0.3, -0.1, 2.0);
    Eigen::Isometry3d T_target = T_host;
    T_target.linear() = T_host.linear() * Eigen::AngleAxisd(0.03, Eigen::Vector3d(0.2, 1.0, 0.1).normalized()).toRotationMatrix();
    T_target.translation() += T_host.linear() * Eigen::Vector3d(0.1, 0.02, 0.8);
    host = factors::toParameters(T_host);
    target = factors::toParameters(T_target);
    ray = testCamera().backProject(250.0, 150.0, 1.0);
  }
};

TEST(WindowFactors, PhotometricJacobiansMatchCentralDifferences) {
  // A blurred bright rectangle whose corner lies 2 px right of and below the projection: the point
  // sits on the flanks of both of its gradient ridges, where the gradient magnitude changes.
  const Scene scene;
  const PinholeCamera camera = testCamera();
  factors::PosePairCache pair;
  const factors::HostToTarget seen(pair.of(scene.host.data(), scene.target.data()), scene.rho, scene.ray, false);
  const Eigen::Vector2d pixel = camera.project(seen.P);
  cv::Mat gray(camera.height, camera.width, CV_8U, cv::Scalar(40));
  cv::rectangle(gray, cv::Point(static_cast<int>(pixel.x()) + 2, static_cast<int>(pixel.y()) + 2), cv::Point(camera.width, camera.height),
                cv::Scalar(220), cv::FILLED);
  cv::GaussianBlur(gray, gray, cv::Size(0, 0), 2.5);
  const ImagePyramid pyramid(gray, camera, 1);
  const cv::Mat& gradient = pyramid.level(0).gradient;
  const ceres::Grid2D<float, 1> grid(gradient.ptr<float>(), 0, gradient.rows, 0, gradient.cols);
  const factors::Interpolator interpolator(grid);
  const factors::PhotometricFactor factor(pair, scene.ray, 5.0, interpolator, camera, 4.0);
  const Derivatives expected = numeric(factor, scene.host, scene.target, scene.rho, 1e-6);
  EXPECT_GT(expected.host.norm(), 1.0);  // the point sees the pattern: the test is not trivial
  expectNear(analytic(factor, scene.host, scene.target, scene.rho), expected, 1e-3);
}

TEST(WindowFactors, EdgeJacobiansMatchCentralDifferences) {
  const PinholeCamera camera = testCamera();
  const Scene scene;
  factors::PosePairCache pair;
  const factors::EdgeFactor factor(pair, scene.ray, Eigen::Vector2d(240.0, 160.0), Eigen::Vector2d(0.6, 0.8), camera, 1.0);
  const Derivatives expected = numeric(factor, scene.host, scene.target, scene.rho, 1e-6);
  EXPECT_GT(expected.host.norm(), 1.0);
  expectNear(analytic(factor, scene.host, scene.target, scene.rho), expected, 1e-4);
}

TEST(WindowFactors, SharedPairCacheFollowsEveryPoseChange) {
  // Factors of one keyframe pair share a cache; Ceres evaluates them at its own candidate states
  // (other buffers, same or other values): each must see the poses it is given, in any order.
  const PinholeCamera camera = testCamera();
  const Scene scene;
  const factors::PoseManifold manifold;
  Vector6d step;
  step << 0.05, -0.02, 0.1, 0.01, -0.02, 0.005;
  PoseParameters moved_host, moved_target;
  manifold.Plus(scene.host.data(), step.data(), moved_host.data());
  manifold.Plus(scene.target.data(), (-step).eval().data(), moved_target.data());
  const Eigen::Vector2d match1(240.0, 160.0), normal1(0.6, 0.8), match2(260.0, 150.0), normal2(0.8, -0.6);
  const auto residual = [&](const ceres::CostFunction& factor, PoseParameters host, PoseParameters target) {
    const double rho = scene.rho;
    const double* parameters[] = {host.data(), target.data(), &rho};
    double value = 0.0;
    EXPECT_TRUE(factor.Evaluate(parameters, &value, nullptr));
    return value;
  };
  /// The residual with a cache of its own, evaluated once.
  const auto alone = [&](const Eigen::Vector2d& match, const Eigen::Vector2d& normal, const PoseParameters& host,
                         const PoseParameters& target) {
    factors::PosePairCache own;
    return residual(factors::EdgeFactor(own, scene.ray, match, normal, camera, 1.0), host, target);
  };
  const double first_at_scene = alone(match1, normal1, scene.host, scene.target);
  const double first_host_moved = alone(match1, normal1, moved_host, scene.target);
  const double first_target_moved = alone(match1, normal1, scene.host, moved_target);
  const double second_at_scene = alone(match2, normal2, scene.host, scene.target);
  ASSERT_GT(std::abs(first_at_scene - first_host_moved), 1.0);  // the steps move the projection
  ASSERT_GT(std::abs(first_at_scene - first_target_moved), 1.0);

  factors::PosePairCache shared;
  const factors::EdgeFactor first(shared, scene.ray, match1, normal1, camera, 1.0);
  const factors::EdgeFactor second(shared, scene.ray, match2, normal2, camera, 1.0);
  EXPECT_EQ(residual(first, scene.host, scene.target), first_at_scene);
  EXPECT_EQ(residual(second, scene.host, scene.target), second_at_scene);
  EXPECT_EQ(residual(first, moved_host, scene.target), first_host_moved);
  EXPECT_EQ(residual(first, scene.host, moved_target), first_target_moved);
  EXPECT_EQ(residual(second, scene.host, scene.target), second_at_scene);
}

/// Residual of a factor over two poses, with its Jacobians when asked for.
template <int N>
Eigen::Matrix<double, N, 1> evaluatePair(const ceres::CostFunction& factor, const PoseParameters& earlier, const PoseParameters& later,
                                         double** jacobians) {
  const double* parameters[] = {earlier.data(), later.data()};
  Eigen::Matrix<double, N, 1> residual;
  EXPECT_TRUE(factor.Evaluate(parameters, residual.data(), jacobians));
  return residual;
}

/// Checks a two-pose factor's analytic Jacobians against central differences through PoseManifold;
/// returns its residual at the scene.
template <int N>
Eigen::Matrix<double, N, 1> expectPairJacobians(const ceres::CostFunction& factor, const Scene& scene) {
  Eigen::Matrix<double, N, 7, Eigen::RowMajor> j_earlier, j_later;
  double* jacobians[] = {j_earlier.data(), j_later.data()};
  const Eigen::Matrix<double, N, 1> residual = evaluatePair<N>(factor, scene.host, scene.target, jacobians);
  EXPECT_EQ(j_earlier.col(6).norm(), 0.0);
  EXPECT_EQ(j_later.col(6).norm(), 0.0);
  const factors::PoseManifold manifold;
  const double step = 1e-6;
  for (int i = 0; i < 6; ++i) {
    Vector6d delta = Vector6d::Zero();
    delta(i) = step;
    PoseParameters plus, minus;
    manifold.Plus(scene.host.data(), delta.data(), plus.data());
    manifold.Plus(scene.host.data(), (-delta).eval().data(), minus.data());
    const Eigen::Matrix<double, N, 1> d_earlier =
        (evaluatePair<N>(factor, plus, scene.target, nullptr) - evaluatePair<N>(factor, minus, scene.target, nullptr)) / (2 * step);
    manifold.Plus(scene.target.data(), delta.data(), plus.data());
    manifold.Plus(scene.target.data(), (-delta).eval().data(), minus.data());
    const Eigen::Matrix<double, N, 1> d_later =
        (evaluatePair<N>(factor, scene.host, plus, nullptr) - evaluatePair<N>(factor, scene.host, minus, nullptr)) / (2 * step);
    EXPECT_LT((j_earlier.col(i) - d_earlier).norm(), 1e-4 * (1.0 + d_earlier.norm())) << "earlier " << i;
    EXPECT_LT((j_later.col(i) - d_later).norm(), 1e-4 * (1.0 + d_later.norm())) << "later " << i;
  }
  return residual;
}

TEST(WindowFactors, ForwardMotionJacobiansMatchCentralDifferences) {
  // The scene's target drifts 0.1 m to the side over 0.8 m: about 7 degrees off the axis.
  const Scene scene(0.5);  // turned in the world: the twists are in the camera frames
  ForwardMotionOptions options;
  options.sigma_deg = 5.0;
  const std::unique_ptr<factors::TravelDirectionFactor> factor(
      factors::forwardMotionFactor(options, factors::fromParameters(scene.host.data()), factors::fromParameters(scene.target.data())));
  EXPECT_GT(expectPairJacobians<2>(*factor, scene).norm(), 1.0);  // about 7 degrees against a 5 degree sigma
}

TEST(WindowFactors, MeasuredMotionIsFreeAtTheTruthAndHasExactJacobians) {
  const Scene scene(0.5);
  const Eigen::Isometry3d T_earlier_later = factors::fromParameters(scene.host.data()).inverse() * factors::fromParameters(scene.target.data());
  const double sigma = 0.5 * M_PI / 180.0;
  const factors::TravelDirectionFactor direction(T_earlier_later.translation(), sigma, T_earlier_later.translation().norm());
  const factors::RelativeRotationFactor rotation(T_earlier_later.linear(), sigma);
  EXPECT_LT(evaluatePair<2>(direction, scene.host, scene.target, nullptr).norm(), 1e-9);
  EXPECT_LT(evaluatePair<3>(rotation, scene.host, scene.target, nullptr).norm(), 1e-9);

  // Measured 1 degree of yaw and about 3 degrees of direction off: residuals of 2 and about 6 sigmas.
  const Eigen::Matrix3d yaw = Eigen::AngleAxisd(M_PI / 180.0, Eigen::Vector3d::UnitY()).toRotationMatrix();
  const Eigen::Matrix3d turn = Eigen::AngleAxisd(3.0 * M_PI / 180.0, Eigen::Vector3d::UnitY()).toRotationMatrix();
  const factors::RelativeRotationFactor rotation_off(T_earlier_later.linear() * yaw, sigma);
  const factors::TravelDirectionFactor direction_off(turn * T_earlier_later.translation(), sigma, T_earlier_later.translation().norm());
  EXPECT_NEAR(expectPairJacobians<3>(rotation_off, scene).norm(), 2.0, 1e-6);
  const Eigen::Vector3d travel = T_earlier_later.translation().normalized();
  const double off = std::acos(travel.dot(turn * travel));  // under 3 degrees: the travel is not across the axis
  EXPECT_NEAR(expectPairJacobians<2>(direction_off, scene).norm(), std::sin(off) / sigma, 1e-6);

  // 20 degrees off about a tilted axis: the Jacobians' second-order terms matter (about 1 %).
  const Eigen::Matrix3d far = Eigen::AngleAxisd(20.0 * M_PI / 180.0, Eigen::Vector3d(0.5, 1.0, 0.3).normalized()).toRotationMatrix();
  const factors::RelativeRotationFactor rotation_far(T_earlier_later.linear() * far, sigma);
  EXPECT_NEAR(expectPairJacobians<3>(rotation_far, scene).norm(), 20.0 / 0.5, 1e-6);
}

TEST(WindowFactors, PoseManifoldPlusAndMinusAreInverse) {
  const Scene scene;
  const factors::PoseManifold manifold;
  Vector6d delta;
  delta << 0.1, -0.2, 0.3, 0.01, -0.02, 0.015;
  PoseParameters moved;
  ASSERT_TRUE(manifold.Plus(scene.host.data(), delta.data(), moved.data()));
  Vector6d back;
  ASSERT_TRUE(manifold.Minus(moved.data(), scene.host.data(), back.data()));
  EXPECT_LT((back - delta).norm(), 1e-9);
}

}  // namespace
}  // namespace semantic_edge_vo
