// The window optimiser's residuals: analytic Jacobians against central differences through the pose
// manifold, the robust rows against Ceres' Huber loss, the shared evaluation at every point Ceres asks for.
#include <gtest/gtest.h>

#include <ceres/loss_function.h>
#include <ceres/crs_matrix.h>
#include <ceres/problem.h>
#include <opencv2/imgproc.hpp>

#include "semantic_edge_vo/backend/factors/relative_rotation_factor.h"
#include "semantic_edge_vo/backend/factors/travel_direction_factor.h"
#include "semantic_edge_vo/backend/factors/window_observations.h"
#include "semantic_edge_vo/frontend/image_pyramid.h"
#include "semantic_edge_vo/backend/window_optimizer.h"

namespace semantic_edge_vo {
namespace {

using factors::PoseParameters;

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

/// The scene's point observed in its target keyframe through WindowObservations, as the window
/// sets it up: the poses, depth and images are the solver's parameter memory, changed in place.
class ObservedScene {
 public:
  static constexpr int kRows = 3;  // photometric, edge, prior

  /// @param edge_offset px from the projection to the edge along its normal
  explicit ObservedScene(double edge_offset = 1.0, const factors::ObservationWeights& weights = WindowOptimizerOptions().observationWeights())
      : poses_{scene_.host, scene_.target}, rho_(scene_.rho) {
    // A blurred bright rectangle whose corner lies 2 px right of and below the projection: the point
    // sits on the flanks of both of its gradient ridges, where the gradient magnitude changes.
    const PinholeCamera camera = testCamera();
    const Eigen::Vector2d pixel = projection();
    cv::Mat gray(camera.height, camera.width, CV_8U, cv::Scalar(40));
    cv::rectangle(gray, cv::Point(static_cast<int>(pixel.x()) + 2, static_cast<int>(pixel.y()) + 2), cv::Point(camera.width, camera.height),
                  cv::Scalar(220), cv::FILLED);
    cv::GaussianBlur(gray, gray, cv::Size(0, 0), 2.5);
    pyramid_ = std::make_unique<ImagePyramid>(gray, camera, 1);
    const cv::Mat& gradient = pyramid_->level(0).gradient;
    grid_ = std::make_unique<ceres::Grid2D<float, 1>>(gradient.ptr<float>(), 0, gradient.rows, 0, gradient.cols);
    image_ = std::make_unique<factors::Interpolator>(*grid_);
    observations_ = std::make_unique<factors::WindowObservations>(poses_, std::vector<const factors::Interpolator*>{image_.get(), image_.get()},
                                                                  camera, weights);
    factors::Observation observation;
    observation.host = 0;
    observation.target = 1;
    observation.host_ray = scene_.ray;
    observation.host_value = 5.0;
    observation.inverse_depth = &rho_;
    observation.has_edge = true;
    observation.normal = Eigen::Vector2d(0.6, 0.8);
    observation.match = pixel - edge_offset * observation.normal;
    observation.has_prior = true;
    observation.prior = 1.1 * scene_.rho;
    observation.prior_sigma = 0.01;
    factor_.reset(observations_->add(observation));
  }

  /// The point's pixel in the target keyframe at the current poses.
  Eigen::Vector2d projection() const {
    return testCamera().project(factors::fromParameters(poses_[1].data()).inverse() * factors::fromParameters(poses_[0].data()) *
                                (scene_.ray / rho_));
  }

  using Rows = Eigen::Matrix<double, kRows, 1>;
  struct Jacobians {
    Eigen::Matrix<double, kRows, 7, Eigen::RowMajor> host, target;
    Rows rho;
  };

  /// The rows at the current parameters as Ceres gets them: the callback first, then the factor.
  Rows evaluate(bool evaluate_jacobians, bool new_point = true, Jacobians* jacobians = nullptr) {
    observations_->PrepareForEvaluation(evaluate_jacobians, new_point);
    const double* parameters[] = {poses_[0].data(), poses_[1].data(), &rho_};
    Rows rows;
    double* blocks[] = {jacobians ? jacobians->host.data() : nullptr, jacobians ? jacobians->target.data() : nullptr,
                        jacobians ? jacobians->rho.data() : nullptr};
    EXPECT_TRUE(factor_->Evaluate(parameters, rows.data(), jacobians ? blocks : nullptr));
    return rows;
  }

  /// Central differences of the rows through PoseManifold::Plus (host, target) and the depth.
  Jacobians numeric(double step) {
    const factors::PoseManifold manifold;
    Jacobians result;
    result.host.setZero();
    result.target.setZero();
    for (int pose = 0; pose < 2; ++pose)
      for (int i = 0; i < 6; ++i) {
        const PoseParameters at = poses_[pose];
        Vector6d delta = Vector6d::Zero();
        delta(i) = step;
        manifold.Plus(at.data(), delta.data(), poses_[pose].data());
        const Rows plus = evaluate(false);
        manifold.Plus(at.data(), (-delta).eval().data(), poses_[pose].data());
        const Rows minus = evaluate(false);
        poses_[pose] = at;
        (pose == 0 ? result.host : result.target).col(i) = (plus - minus) / (2 * step);
      }
    const double at = rho_, rho_step = step * rho_;
    rho_ = at + rho_step;
    const Rows plus = evaluate(false);
    rho_ = at - rho_step;
    const Rows minus = evaluate(false);
    rho_ = at;
    result.rho = (plus - minus) / (2 * rho_step);
    return result;
  }

  std::vector<PoseParameters>& poses() { return poses_; }
  double* inverseDepth() { return &rho_; }
  factors::WindowObservations& observations() { return *observations_; }
  const ceres::CostFunction& factor() const { return *factor_; }
  /// The remainder block's row at the last evaluation.
  double remainderRow() const {
    const std::unique_ptr<ceres::CostFunction> block(observations_->remainderBlock());
    const double* parameters[] = {poses_[1].data()};
    double row = -1.0;
    EXPECT_TRUE(block->Evaluate(parameters, &row, nullptr));
    return row;
  }

 private:
  Scene scene_;
  std::vector<PoseParameters> poses_;
  double rho_;
  std::unique_ptr<ImagePyramid> pyramid_;
  std::unique_ptr<ceres::Grid2D<float, 1>> grid_;
  std::unique_ptr<factors::Interpolator> image_;
  std::unique_ptr<factors::WindowObservations> observations_;
  std::unique_ptr<ceres::CostFunction> factor_;
};

TEST(WindowFactors, ObservationJacobiansMatchCentralDifferences) {
  ObservedScene observed;  // every row within its Huber threshold: the rows are the residuals
  ObservedScene::Jacobians analytic;
  const ObservedScene::Rows rows = observed.evaluate(true, true, &analytic);
  const ObservedScene::Jacobians expected = observed.numeric(1e-6);
  EXPECT_GT(expected.host.row(0).norm(), 1.0);  // the point sees the pattern: the test is not trivial
  EXPECT_LT(std::abs(rows(0)), 9.0 / 4.0);
  EXPECT_NEAR(rows(1), std::sqrt(0.5) * 1.0, 1e-6);       // 1 px at the edge weight 0.5
  EXPECT_NEAR(rows(2), -0.1 * (1.0 / 12.0) / 0.01, 1e-9);  // (rho - 1.1 rho) / sigma
  EXPECT_EQ(observed.remainderRow(), 0.0);
  EXPECT_EQ(analytic.host.col(6).norm(), 0.0);
  EXPECT_EQ(analytic.target.col(6).norm(), 0.0);
  for (int row = 0; row < ObservedScene::kRows; ++row) {
    for (int i = 0; i < 6; ++i) {
      EXPECT_NEAR(analytic.host(row, i), expected.host(row, i), 1e-3 * (1.0 + std::abs(expected.host(row, i)))) << row << " host " << i;
      EXPECT_NEAR(analytic.target(row, i), expected.target(row, i), 1e-3 * (1.0 + std::abs(expected.target(row, i)))) << row << " target " << i;
    }
    EXPECT_NEAR(analytic.rho(row), expected.rho(row), 1e-3 * (1.0 + std::abs(expected.rho(row)))) << row;
  }
  EXPECT_EQ(expected.host.row(2).norm() + expected.target.row(2).norm(), 0.0);  // the prior is on the depth alone
}

TEST(WindowFactors, AnOutlierRowIsReweightedAndItsCostKept) {
  // The edge 3 px away, twice the Huber threshold: its row and Jacobian are the residual's scaled by
  // sqrt(rho'), as Ceres' loss functions present them, and the remainder block carries the rest.
  ObservedScene inlier(1.0), outlier(3.0);
  ObservedScene::Jacobians near, far;
  inlier.evaluate(true, true, &near);
  const ObservedScene::Rows rows = outlier.evaluate(true, true, &far);
  const double w = 0.5, k = 1.5, r = 3.0;
  const double scale = std::sqrt(w * k / r);
  EXPECT_NEAR(rows(1), scale * r, 1e-6);
  // The same projection: only the match moved, so the raw residual's derivatives are the same.
  const double ratio = scale / std::sqrt(w);
  EXPECT_LT((far.host.row(1) - ratio * near.host.row(1)).norm(), 1e-9 * (1.0 + near.host.row(1).norm()));
  EXPECT_LT((far.target.row(1) - ratio * near.target.row(1)).norm(), 1e-9 * (1.0 + near.target.row(1).norm()));
  EXPECT_EQ(far.host.row(0), near.host.row(0));
  // Half the squares of the row and of the remainder block: the robust cost, w (2 k r - k^2) / 2.
  const double remainder = outlier.remainderRow();
  EXPECT_NEAR(0.5 * (rows(1) * rows(1) + remainder * remainder), 0.5 * w * (2 * k * r - k * k), 1e-9);
}

TEST(WindowFactors, RobustRowIsCeresHuberLoss) {
  // Ceres' cost (rho), its IRLS weight (rho') and so its gradient, for every residual.
  const double k = 1.5;
  for (const double w : {1.0, 0.5}) {
    const ceres::ScaledLoss loss(new ceres::HuberLoss(k), w, ceres::TAKE_OWNERSHIP);
    for (const double r : {-7.0, -1.6, -0.3, 0.0, 1.0, 1.5, 2.5, 40.0}) {
      double rho[3];
      loss.Evaluate(r * r, rho);
      const factors::RobustRow row = factors::robustRow(r, k, w);
      EXPECT_NEAR(row.residual * row.residual + row.remainder, rho[0], 1e-12 * (1.0 + rho[0])) << r;
      EXPECT_NEAR(row.scale * row.scale, rho[1], 1e-12) << r;
      EXPECT_NEAR(row.residual, row.scale * r, 1e-12 * (1.0 + std::abs(r))) << r;
      EXPECT_EQ(row.remainder == 0.0, std::abs(r) <= k) << r;
    }
  }
}

/// Row `row` of a block as a block of its own: the reference problem, one residual per block.
class RowOf : public ceres::CostFunction {
 public:
  RowOf(const ceres::CostFunction& block, int row) : block_(block), row_(row) {
    set_num_residuals(1);
    *mutable_parameter_block_sizes() = block.parameter_block_sizes();
  }

  bool Evaluate(const double* const* parameters, double* residuals, double** jacobians) const override {
    const int rows = block_.num_residuals();
    std::vector<double> all(static_cast<std::size_t>(rows));
    std::vector<std::vector<double>> all_jacobians;
    std::vector<double*> pointers;
    for (const int size : block_.parameter_block_sizes()) {
      all_jacobians.emplace_back(static_cast<std::size_t>(rows * size));
      pointers.push_back(all_jacobians.back().data());
    }
    if (!block_.Evaluate(parameters, all.data(), jacobians ? pointers.data() : nullptr)) return false;
    residuals[0] = all[static_cast<std::size_t>(row_)];
    if (!jacobians) return true;
    for (std::size_t b = 0; b < all_jacobians.size(); ++b) {
      if (!jacobians[b]) continue;
      const int size = block_.parameter_block_sizes()[b];
      std::copy_n(all_jacobians[b].begin() + row_ * size, size, jacobians[b]);
    }
    return true;
  }

 private:
  const ceres::CostFunction& block_;
  int row_;
};

/// The gradient and the Gauss-Newton matrix J^T J of a problem at its parameters.
struct Model {
  double cost = 0.0;
  Eigen::VectorXd gradient;
  Eigen::MatrixXd normal;
};
Model modelOf(ceres::Problem& problem) {
  Model model;
  std::vector<double> gradient;
  ceres::CRSMatrix jacobian;
  EXPECT_TRUE(problem.Evaluate(ceres::Problem::EvaluateOptions(), &model.cost, nullptr, &gradient, &jacobian));
  model.gradient = Eigen::Map<Eigen::VectorXd>(gradient.data(), static_cast<Eigen::Index>(gradient.size()));
  Eigen::MatrixXd dense = Eigen::MatrixXd::Zero(jacobian.num_rows, jacobian.num_cols);
  for (int row = 0; row < jacobian.num_rows; ++row)
    for (int k = jacobian.rows[static_cast<std::size_t>(row)]; k < jacobian.rows[static_cast<std::size_t>(row) + 1]; ++k)
      dense(row, jacobian.cols[static_cast<std::size_t>(k)]) = jacobian.values[static_cast<std::size_t>(k)];
  model.normal = dense.transpose() * dense;
  return model;
}

TEST(WindowFactors, TheSolverSeesWhatOneCeresLossPerResidualGives) {
  // The window's problem (rows reweighted by the callback, the remainder block) against the same
  // residuals given to Ceres one block each with its HuberLoss / ScaledLoss: the same cost, gradient
  // and Gauss-Newton matrix, the edge row 3 px out (twice its Huber threshold).
  const factors::ObservationWeights weights = WindowOptimizerOptions().observationWeights();
  factors::ObservationWeights plain_weights = weights;  // no robust weighting: the plain residuals
  plain_weights.photometric_huber = plain_weights.edge_huber = 1e12;
  plain_weights.edge_weight = 1.0;
  ObservedScene window(3.0, weights), plain(3.0, plain_weights);

  factors::PoseManifold manifold;
  ceres::Problem::Options options;
  options.cost_function_ownership = options.loss_function_ownership = options.manifold_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  options.evaluation_callback = &window.observations();
  ceres::Problem solved_as(options);  // as the window solves it
  options.evaluation_callback = &plain.observations();
  ceres::Problem reference(options);
  for (ObservedScene* scene : {&window, &plain}) {
    ceres::Problem& problem = scene == &window ? solved_as : reference;
    for (PoseParameters& pose : scene->poses()) problem.AddParameterBlock(pose.data(), 7, &manifold);
    problem.AddParameterBlock(scene->inverseDepth(), 1);
  }
  double* const window_blocks[] = {window.poses()[0].data(), window.poses()[1].data(), window.inverseDepth()};
  double* const plain_blocks[] = {plain.poses()[0].data(), plain.poses()[1].data(), plain.inverseDepth()};
  solved_as.AddResidualBlock(const_cast<ceres::CostFunction*>(&window.factor()), nullptr, window_blocks, 3);
  const std::unique_ptr<ceres::CostFunction> remainder(window.observations().remainderBlock());
  solved_as.AddResidualBlock(remainder.get(), nullptr, window.poses()[1].data());

  ceres::HuberLoss photometric_loss(weights.photometric_huber / weights.photometric_sigma);
  ceres::ScaledLoss edge_loss(new ceres::HuberLoss(weights.edge_huber / weights.edge_sigma), weights.edge_weight, ceres::TAKE_OWNERSHIP);
  ceres::LossFunction* const losses[] = {&photometric_loss, &edge_loss, nullptr};
  std::vector<std::unique_ptr<RowOf>> rows;
  for (int row = 0; row < ObservedScene::kRows; ++row) {
    rows.push_back(std::make_unique<RowOf>(plain.factor(), row));
    reference.AddResidualBlock(rows.back().get(), losses[row], plain_blocks, 3);
  }

  const Model got = modelOf(solved_as), expected = modelOf(reference);
  EXPECT_GT(window.remainderRow(), 0.0);  // the edge row is an outlier: the test is not trivial
  EXPECT_NEAR(got.cost, expected.cost, 1e-9 * expected.cost);
  ASSERT_EQ(got.gradient.size(), expected.gradient.size());
  EXPECT_LT((got.gradient - expected.gradient).norm(), 1e-9 * (1.0 + expected.gradient.norm()));
  EXPECT_LT((got.normal - expected.normal).norm(), 1e-9 * (1.0 + expected.normal.norm()));
}

TEST(WindowFactors, ObservationsFollowEveryEvaluationPoint) {
  // Ceres evaluates candidate points, goes back, and asks for Jacobians at a point it evaluated
  // without: each time the rows must be those of the parameters it set.
  const factors::PoseManifold manifold;
  Vector6d step;
  step << 0.05, -0.02, 0.1, 0.01, -0.02, 0.005;
  ObservedScene observed;
  const ObservedScene::Rows at_scene = observed.evaluate(false);
  const PoseParameters host = observed.poses()[0];
  manifold.Plus(host.data(), step.data(), observed.poses()[0].data());
  const ObservedScene::Rows moved = observed.evaluate(false);
  ASSERT_GT((moved - at_scene).norm(), 0.5);  // the step moves the projection
  ObservedScene fresh;  // the same scene, evaluated only at the moved point
  fresh.poses()[0] = observed.poses()[0];
  EXPECT_EQ(fresh.evaluate(false), moved);
  observed.poses()[0] = host;
  EXPECT_EQ(observed.evaluate(false), at_scene);

  ObservedScene::Jacobians later, direct;
  EXPECT_EQ(observed.evaluate(true, false, &later), at_scene);  // Jacobians after a residual-only evaluation there
  ObservedScene reference;
  reference.evaluate(true, true, &direct);
  EXPECT_EQ(later.host, direct.host);
  EXPECT_EQ(later.target, direct.target);
  EXPECT_EQ(later.rho, direct.rho);
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
