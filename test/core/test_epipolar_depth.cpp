#include <cmath>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>

#include "semantic_edge_vo/epipolar_depth.h"
#include "semantic_edge_vo/image_pyramid.h"
#include "semantic_edge_vo/nearest_neighbor_field.h"
#include "semantic_edge_vo/shared_class_edge_test.h"

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

// A facade of stripes 0.5 m apart (25 px at 10 m), seen by a camera moving 0.1 m, then 1 m to its
// right; the prior (0.1 +- 0.05 /m, as propagated) spans disparities 0-112 px on the 1 m line.
constexpr double kStripePeriod = 0.5;

cv::Mat renderFacade(double camera_x) {
  const PinholeCamera c = camera();
  cv::Mat image(c.height, c.width, CV_8UC1);
  for (int u = 0; u < c.width; ++u) {
    const double x = (u - c.cx) / c.fx * kDepth + camera_x;
    const double value = 100.0 + 60.0 * std::tanh(4.0 * std::sin(2.0 * M_PI * x / kStripePeriod));
    for (int v = 0; v < c.height; ++v) image.at<std::uint8_t>(v, u) = cv::saturate_cast<std::uint8_t>(value);
  }
  return image;
}

class EpipolarFacade : public ::testing::Test {
 protected:
  EpipolarFacade()
      : host_(renderFacade(0.0), camera(), 1),
        near_(renderFacade(0.1), camera(), 1),
        nearest_(renderFacade(0.02), camera(), 1),
        far_(renderFacade(kBaseline), camera(), 1) {
    point_.u = static_cast<float>(camera().cx);  // a stripe's edge (x = 0)
    point_.v = 100.0f;
    point_.inverse_depth = 1.0 / kDepth;
    point_.inverse_depth_variance = std::pow(0.5 / kDepth, 2);
    near_target_.level = &near_.level(0);
    near_target_.T_target_host.translation() = Eigen::Vector3d(-0.1, 0.0, 0.0);
    nearest_target_.level = &nearest_.level(0);
    nearest_target_.T_target_host.translation() = Eigen::Vector3d(-0.02, 0.0, 0.0);
    far_target_.level = &far_.level(0);
    far_target_.T_target_host.translation() = Eigen::Vector3d(-kBaseline, 0.0, 0.0);
  }

  ImagePyramid host_, near_, nearest_, far_;
  EpipolarTarget near_target_, nearest_target_, far_target_;
  MapPoint point_;
};

TEST_F(EpipolarFacade, TheLongLineAloneFindsEveryStripeAlike) {
  DepthMeasurement measurement;
  const bool found = searchEpipolarNarrowed(point_, host_.level(0), nullptr, far_target_, EpipolarSearchOptions(), &measurement);
  EXPECT_TRUE(!found || std::abs(measurement.inverse_depth - 1.0 / kDepth) > 0.01) << measurement.inverse_depth;
}

TEST_F(EpipolarFacade, TheShortLineNarrowsTheLongOneToTheRightStripe) {
  DepthMeasurement measurement;
  ASSERT_TRUE(searchEpipolarNarrowed(point_, host_.level(0), &near_target_, far_target_, EpipolarSearchOptions(), &measurement));
  EXPECT_NEAR(measurement.inverse_depth, 1.0 / kDepth, 0.002);
  // Measured on the long line (ten times the baseline): well under the short one's sigma.
  DepthMeasurement near_only;
  ASSERT_TRUE(searchEpipolar(point_, host_.level(0), near_.level(0), nullptr, near_target_.T_target_host, EpipolarSearchOptions(), &near_only));
  EXPECT_LT(std::sqrt(measurement.variance), 0.2 * std::sqrt(near_only.variance));
}

TEST_F(EpipolarFacade, AMatchLessCertainThanThePriorLeavesTheSearchToThePrior) {
  // 0.02 m: a line of about 2 px, whose match is less certain than the prior (0.7 px of 10 px per 1/m).
  DepthMeasurement narrowed, plain;
  const bool narrowed_found =
      searchEpipolarNarrowed(point_, host_.level(0), &nearest_target_, far_target_, EpipolarSearchOptions(), &narrowed);
  const bool plain_found = searchEpipolarNarrowed(point_, host_.level(0), nullptr, far_target_, EpipolarSearchOptions(), &plain);
  ASSERT_EQ(narrowed_found, plain_found);
  if (plain_found) EXPECT_EQ(narrowed.inverse_depth, plain.inverse_depth);
  DepthMeasurement nearest_only;
  ASSERT_TRUE(searchEpipolar(point_, host_.level(0), nearest_.level(0), nullptr, nearest_target_.T_target_host, EpipolarSearchOptions(),
                             &nearest_only))
      << "the short line has a match, only too uncertain to narrow";
  EXPECT_GT(nearest_only.variance, point_.inverse_depth_variance);
}

}  // namespace
}  // namespace semantic_edge_vo
