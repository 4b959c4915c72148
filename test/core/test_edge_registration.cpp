#include <gtest/gtest.h>

#include "line_scene.h"
#include "semantic_edge_vo/common/robust_statistics.h"

namespace semantic_edge_vo {
namespace {

using testing_scenes::LineScene;
using testing_scenes::pose;

TEST(Se3, ExpLogRoundTrip) {
  Vector6d twist;
  twist << 0.3, -1.2, 2.0, 0.1, -0.4, 0.25;
  EXPECT_TRUE(se3Log(se3Exp(twist)).isApprox(twist, 1e-10));
  EXPECT_TRUE(se3Exp(Vector6d::Zero()).isApprox(Eigen::Isometry3d::Identity()));
}

TEST(EdgeRegistration, JacobianMatchesNumericDifferentiation) {
  const PinholeCamera camera = kittiCamera();
  // One seed per layer: the association cannot jump while we differentiate.
  EdgeSet target;
  target.push_back(600.0f, 200.0f, 0.6f, 0.8f, 1.0f, 1u);
  FieldOptions field_options;
  field_options.kind = FieldKind::kAnnf;
  field_options.pyramid_levels = 1;
  field_options.truncation_radius = 500.0f;
  const auto data = buildNearestNeighborField(target.view(), camera.width, camera.height, {}, field_options);
  const auto field = data.view();
  const std::vector<ReferenceEdge> edges = {{Eigen::Vector3d(1.5, -0.7, 12.0), Eigen::Vector2d(1, 0), 1u, 1.0}};
  EdgeRegistration registration(camera, EdgeRegistrationOptions());
  const Eigen::Isometry3d T = pose(0.2, -0.1, 0.5, 3.0, 1.0);
  const auto at = registration.residuals(edges, field, T);
  ASSERT_EQ(at.size(), 1u);
  const double eps = 1e-6;
  for (int i = 0; i < 6; ++i) {
    Vector6d delta = Vector6d::Zero();
    delta[i] = eps;
    const double plus = registration.residuals(edges, field, se3Exp(delta) * T)[0].value;
    const double minus = registration.residuals(edges, field, se3Exp(-delta) * T)[0].value;
    EXPECT_NEAR(at[0].jacobian[i], (plus - minus) / (2 * eps), 1e-4 * std::max(1.0, std::abs(at[0].jacobian[i])))
        << "twist component " << i;
  }
}

// An edge pixel labelled with three classes, projected 1 px right of a class-0 edge and 5 px left of
// a class-1 edge; class 2 has no edge near: one residual per class it meets (Eq. 10).
TEST(EdgeRegistration, PixelOfSeveralClassesMeetsEachOfThem) {
  const PinholeCamera camera = kittiCamera();
  EdgeSet target;
  target.push_back(600.0f, 200.0f, 1.0f, 0.0f, 1.0f, 1u << 0);
  target.push_back(606.0f, 200.0f, 1.0f, 0.0f, 1.0f, 1u << 1);
  FieldOptions field_options;
  field_options.kind = FieldKind::kSnnf;
  field_options.pyramid_levels = 1;
  field_options.truncation_radius = 20.0f;
  const auto data = buildNearestNeighborField(target.view(), camera.width, camera.height, {"a", "b", "c"}, field_options);
  const std::vector<ReferenceEdge> edges = {{camera.backProject(601.0, 200.0, 10.0), Eigen::Vector2d(1, 0), 0b111u, 2.0}};
  const Eigen::Isometry3d identity = Eigen::Isometry3d::Identity();
  EdgeRegistrationOptions options;
  options.huber_threshold = 10.0;  // quadratic over these distances: cost = weight * r^2 / 2
  std::vector<EdgeResidual> residuals;
  const double cost = EdgeRegistration(camera, options).evaluate(edges, data.view(), identity, &residuals);
  ASSERT_EQ(residuals.size(), 2u);
  EXPECT_NEAR(residuals[0].value, 1.0, 1e-4);
  EXPECT_NEAR(residuals[1].value, -5.0, 1e-4);
  const double unmatched = huberCost(20.0, 10.0);  // class 2: nothing within the truncation radius
  EXPECT_NEAR(cost, 2.0 * (0.5 + 12.5 + unmatched), 1e-3);
  EXPECT_NEAR(residuals[0].weight, 2.0, 1e-9);
}

class RegistrationRecovers : public ::testing::TestWithParam<FieldKind> {};

TEST_P(RegistrationRecovers, KnownPoseFromAPerturbedStart) {
  const PinholeCamera camera = kittiCamera();
  const LineScene scene = LineScene::random(120, 6, 3);
  const Eigen::Isometry3d T_ref_world = Eigen::Isometry3d::Identity();
  const Eigen::Isometry3d T_target_world = pose(0.1, 0.0, -1.5, 1.0);  // driving forward 1.5 m, turning 1 deg
  const EdgeSet target = scene.edgesIn(camera, T_target_world);
  FieldOptions field_options;
  field_options.kind = GetParam();
  field_options.pyramid_levels = 1;
  const std::vector<std::string> classes(6, "c");
  const auto data = buildNearestNeighborField(target.view(), camera.width, camera.height, classes, field_options);
  const std::vector<ReferenceEdge> edges = scene.referenceEdges(camera, T_ref_world);
  ASSERT_GT(edges.size(), 300u);

  const Eigen::Isometry3d truth = T_target_world * T_ref_world.inverse();
  const Eigen::Isometry3d start = pose(0.15, -0.05, 0.2, 0.5) * truth;  // 0.25 m and 0.5 deg off
  const EdgeRegistrationResult result = EdgeRegistration(camera, EdgeRegistrationOptions()).align(edges, data.view(), start);
  const Eigen::Isometry3d error = result.T_target_ref * truth.inverse();
  EXPECT_LT(error.translation().norm(), 0.01) << toString(GetParam());
  EXPECT_LT(Eigen::AngleAxisd(error.linear()).angle() * 180 / M_PI, 0.02) << toString(GetParam());
  EXPECT_GT(result.inliers, static_cast<int>(edges.size() / 2));
  EXPECT_LT(result.rmse, 0.3);
}

INSTANTIATE_TEST_SUITE_P(AllKinds, RegistrationRecovers,
                         ::testing::Values(FieldKind::kAnnf, FieldKind::kOnnf, FieldKind::kSnnf),
                         [](const auto& info) { return std::string(toString(info.param)); });

}  // namespace
}  // namespace semantic_edge_vo
