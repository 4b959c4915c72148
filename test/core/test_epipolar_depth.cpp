#include <cmath>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>

#include "semantic_edge_vo/backend/epipolar_depth.h"
#include "semantic_edge_vo/frontend/image_pyramid.h"
#include "semantic_edge_vo/fields/nearest_neighbor_field.h"
#include "semantic_edge_vo/fields/shared_class_edge_test.h"

namespace semantic_edge_vo {
namespace {

// A wall 10 m ahead with vertical steps in brightness, seen by a camera that moves 1 m to its right:
// the epipolar lines are rows, each step shifts 50 px to the left.
constexpr double kDepth = 10.0, kBaseline = 1.0;
constexpr double kStepX[] = {-2.0, -1.0, 0.0, 0.6, 1.5};      // m, along the wall
constexpr double kStepHeight[] = {30.0, 50.0, -40.0, 70.0, -60.0};  // gray levels: each step looks different

PinholeCamera camera() {
  PinholeCamera c;
  c.fx = c.fy = 500.0;
  c.cx = 160.0;
  c.cy = 100.0;
  c.width = 320;
  c.height = 200;
  return c;
}

double wallBrightness(double x) {
  double value = 60.0;
  for (std::size_t k = 0; k < std::size(kStepX); ++k) value += kStepHeight[k] / (1.0 + std::exp(-(x - kStepX[k]) / 0.02));
  return value;
}

cv::Mat render(double camera_x) {
  const PinholeCamera c = camera();
  cv::Mat image(c.height, c.width, CV_8UC1);
  for (int u = 0; u < c.width; ++u) {
    const double value = wallBrightness((u - c.cx) / c.fx * kDepth + camera_x);
    for (int v = 0; v < c.height; ++v) image.at<std::uint8_t>(v, u) = cv::saturate_cast<std::uint8_t>(value);
  }
  return image;
}

double columnOf(double wall_x, double camera_x) { return camera().cx + camera().fx * (wall_x - camera_x) / kDepth; }

/// The target's field: every step an edge down the whole image, of the given classes.
NearestNeighborFieldData targetField(const std::vector<std::uint32_t>& step_classes) {
  EdgeSet edges;
  for (std::size_t k = 0; k < std::size(kStepX); ++k)
    for (int v = 0; v < camera().height; ++v)
      edges.push_back(static_cast<float>(columnOf(kStepX[k], kBaseline)), static_cast<float>(v), 1.0f, 0.0f, 1.0f, step_classes[k]);
  FieldOptions options;
  options.kind = FieldKind::kSnnf;
  options.pyramid_levels = 1;
  return buildNearestNeighborField(edges.view(), camera().width, camera().height, {"a", "b", "c"}, options);
}

class EpipolarEdgeClasses : public ::testing::Test {
 protected:
  EpipolarEdgeClasses() : host_(render(0.0), camera(), 1), target_(render(kBaseline), camera(), 1) {
    T_target_host_.translation() = Eigen::Vector3d(-kBaseline, 0.0, 0.0);
    // The step at 0.6 m, class b, prior 0.1 +- 0.03 /m: its line in the target passes the step at 0 m too.
    point_.u = static_cast<float>(columnOf(0.6, 0.0));
    point_.v = 100.0f;
    point_.class_mask = 1u << 1;
    point_.field_layers = point_.class_mask;  // its class is relied on: matched in its own layer
    point_.normal = Eigen::Vector2f(1.0f, 0.0f);
    point_.inverse_depth = 1.0 / kDepth;
    point_.inverse_depth_variance = 0.03 * 0.03;
  }

  /// Searches the point with the target's steps of these classes; the measured inverse depth or -1.
  double search(const std::vector<std::uint32_t>& step_classes) const {
    const NearestNeighborFieldData field = targetField(step_classes);
    const NearestNeighborFieldView view = field.view();
    const SharedClassEdgeTest edges(view, EpipolarSearchOptions().edge_radius);
    DepthMeasurement measurement;
    if (!searchEpipolar(point_, host_.level(0), target_.level(0), &edges, T_target_host_, EpipolarSearchOptions(), &measurement))
      return -1.0;
    return measurement.inverse_depth;
  }

  ImagePyramid host_, target_;
  Eigen::Isometry3d T_target_host_ = Eigen::Isometry3d::Identity();
  MapPoint point_;
};

constexpr std::uint32_t kA = 1u << 0, kB = 1u << 1, kC = 1u << 2;

TEST_F(EpipolarEdgeClasses, MatchesTheEdgeOfItsClass) {
  EXPECT_NEAR(search({kA, kA, kA, kB, kA}), 1.0 / kDepth, 0.002);
}

TEST_F(EpipolarEdgeClasses, AnEdgeOfItsClassElsewhereOnTheLineKeepsTheSearchThere) {
  // The true match lost the point's class; another step on the line has it: the search stays with
  // the class and finds no match (or a wrong one), never the step of the other class.
  const double measured = search({kA, kA, kB, kC, kA});
  EXPECT_TRUE(measured < 0.0 || std::abs(measured - 1.0 / kDepth) > 0.01) << measured;
}

TEST_F(EpipolarEdgeClasses, WithoutItsClassAnywhereOnTheLineAnyEdgeWillDo) {
  // A label that flickered: the point's class is nowhere in the target, the true step is found.
  EXPECT_NEAR(search({kA, kA, kA, kC, kA}), 1.0 / kDepth, 0.002);
}

TEST_F(EpipolarEdgeClasses, SupportivePointsIgnoreEdges) {
  point_.class_mask = 0;
  EXPECT_NEAR(search({kA, kA, kA, 0u, kA}), 1.0 / kDepth, 0.002) << "the true step has no edge in the target";
}

}  // namespace
}  // namespace semantic_edge_vo
