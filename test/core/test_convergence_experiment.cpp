#include <gtest/gtest.h>

#include "line_scene.h"
#include "semantic_edge_vo/experiments/convergence_experiment.h"

namespace semantic_edge_vo {
namespace {

using testing_scenes::LineScene;
using testing_scenes::pose;

std::vector<RegistrationProblem> problems() {
  std::vector<RegistrationProblem> out;
  for (std::uint32_t seed : {5u, 6u}) {
    const LineScene scene = LineScene::random(120, 6, seed);
    RegistrationProblem p;
    p.camera = kittiCamera();
    const Eigen::Isometry3d T_target_world = pose(0.0, 0.0, -1.2, 0.5);
    p.reference = scene.referenceEdges(p.camera, Eigen::Isometry3d::Identity());
    p.target_edges = scene.edgesIn(p.camera, T_target_world);
    p.class_names.assign(6, "c");
    p.T_target_ref = T_target_world;
    out.push_back(std::move(p));
  }
  return out;
}

TEST(ConvergenceExperiment, SucceedsWhenStartedAtTheTruthAndFailsFarAway) {
  ConvergenceOptions options;
  options.displacements_m = {0.0, 0.3, 20.0};
  options.rotations_deg = {0.0, 60.0};
  options.trials = 4;
  ASSERT_EQ(options.validate(), "");
  const ConvergenceCurve curve = runConvergence(problems(), FieldKind::kSnnf, options);
  ASSERT_EQ(curve.translation.size(), 3u);
  EXPECT_EQ(curve.translation[0].trials, 8);
  EXPECT_DOUBLE_EQ(curve.translation[0].success_rate, 1.0);
  EXPECT_LT(curve.translation[0].median_error_m, 1e-3);
  EXPECT_DOUBLE_EQ(curve.translation[1].success_rate, 1.0);
  EXPECT_LT(curve.translation[2].success_rate, 0.5) << "20 m away cannot converge";
  EXPECT_DOUBLE_EQ(curve.basin_m, 0.3);
  EXPECT_LT(curve.rotation[1].success_rate, 0.5);
  EXPECT_DOUBLE_EQ(curve.basin_deg, 0.0);
}

TEST(ConvergenceExperiment, DeterministicForASeed) {
  ConvergenceOptions options;
  options.displacements_m = {1.0};
  options.rotations_deg = {2.0};
  options.trials = 3;
  const auto a = runConvergence(problems(), FieldKind::kAnnf, options);
  const auto b = runConvergence(problems(), FieldKind::kAnnf, options);
  EXPECT_EQ(convergenceJson({a}, "x"), convergenceJson({b}, "x"));
}

TEST(ConvergenceExperiment, BasinNeedsEverySmallerDisplacementToSucceed) {
  std::vector<ConvergenceRow> rows(4);
  const double success[] = {1.0, 0.6, 0.4, 0.9};
  for (int i = 0; i < 4; ++i) {
    rows[i].displacement = i;
    rows[i].success_rate = success[i];
  }
  EXPECT_DOUBLE_EQ(basinOf(rows), 1.0);
  rows[0].success_rate = 0.2;
  EXPECT_DOUBLE_EQ(basinOf(rows), 0.0);
}

TEST(ConvergenceExperiment, JsonHasEveryKindWithBasinAndRows) {
  ConvergenceCurve curve;
  curve.kind = FieldKind::kOnnf;
  curve.basin_m = 1.5;
  curve.translation.push_back({1.5, 0.01, 0.1, 0.75, 20});
  const std::string json = convergenceJson({curve}, "a \"quoted\" scene");
  EXPECT_NE(json.find("\"onnf\": {\"basin_m\": 1.5"), std::string::npos) << json;
  EXPECT_NE(json.find("\"success_rate\": 0.75"), std::string::npos) << json;
  EXPECT_NE(json.find("a \\\"quoted\\\" scene"), std::string::npos) << json;
}

}  // namespace
}  // namespace semantic_edge_vo
