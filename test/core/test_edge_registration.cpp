#include <random>

#include <gtest/gtest.h>

#include "semantic_edge_vo/edge_registration.h"

namespace semantic_edge_vo {
namespace {

/// 3D line segments with classes, seen by two cameras: edges of the target image (for its field)
/// and reference edges with exact depth.
struct LineScene {
  struct Segment {
    Eigen::Vector3d a, b;
    int label;
  };
  std::vector<Segment> segments;

  static LineScene random(int count, int classes, std::uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> x(-12, 12), y(-4, 3), z(6, 40), len(1.0, 6.0), dir(-1, 1);
    std::uniform_int_distribution<int> label(0, classes - 1);
    LineScene scene;
    for (int i = 0; i < count; ++i) {
      const Eigen::Vector3d a(x(rng), y(rng), z(rng));
      const Eigen::Vector3d d = Eigen::Vector3d(dir(rng), dir(rng), 0.3 * dir(rng)).normalized();
      scene.segments.push_back({a, a + len(rng) * d, label(rng)});
    }
    return scene;
  }

  /// Edge pixels of the segments seen from a camera at T_cam_world, one per ~0.5 px.
  EdgeSet edgesIn(const PinholeCamera& camera, const Eigen::Isometry3d& T_cam_world) const {
    EdgeSet edges;
    for (const Segment& s : segments) {
      const Eigen::Vector3d a = T_cam_world * s.a, b = T_cam_world * s.b;
      if (a.z() < 1 || b.z() < 1) continue;
      const Eigen::Vector2d pa = camera.project(a), pb = camera.project(b);
      const int steps = static_cast<int>((pb - pa).norm() * 2) + 1;
      const Eigen::Vector2d t = (pb - pa).normalized();
      for (int k = 0; k <= steps; ++k) {
        const Eigen::Vector3d p = T_cam_world * (s.a + (s.b - s.a) * k / steps);
        const Eigen::Vector2d q = camera.project(p);
        if (!camera.contains(q.x(), q.y(), 1)) continue;
        edges.push_back(static_cast<float>(q.x()), static_cast<float>(q.y()), static_cast<float>(-t.y()),
                        static_cast<float>(t.x()), 1.0f, 1u << s.label);
      }
    }
    return edges;
  }
  /// Reference edges (points in the reference optical frame) every `spacing` metres.
  std::vector<ReferenceEdge> referenceEdges(const PinholeCamera& camera, const Eigen::Isometry3d& T_ref_world) const {
    std::vector<ReferenceEdge> out;
    for (const Segment& s : segments) {
      const Eigen::Vector3d a = T_ref_world * s.a, b = T_ref_world * s.b;
      if (a.z() < 1 || b.z() < 1) continue;
      const Eigen::Vector2d t = (camera.project(b) - camera.project(a)).normalized();
      for (int k = 0; k <= 8; ++k) {
        const Eigen::Vector3d p = a + (b - a) * k / 8.0;
        const Eigen::Vector2d q = camera.project(p);
        if (!camera.contains(q.x(), q.y(), 1)) continue;
        out.push_back({p, Eigen::Vector2d(-t.y(), t.x()), 1u << s.label, 1.0});
      }
    }
    return out;
  }
};

Eigen::Isometry3d pose(double tx, double ty, double tz, double yaw_deg, double pitch_deg = 0) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.rotate(Eigen::AngleAxisd(yaw_deg * M_PI / 180, Eigen::Vector3d::UnitY()) *
           Eigen::AngleAxisd(pitch_deg * M_PI / 180, Eigen::Vector3d::UnitX()));
  T.translation() << tx, ty, tz;
  return T;
}

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
