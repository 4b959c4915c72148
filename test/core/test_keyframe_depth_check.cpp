#include <gtest/gtest.h>

#include "semantic_edge_vo/keyframe_depth_check.h"

namespace semantic_edge_vo {
namespace {

/// A slanted plane, 10 m at the left border to 20 m at the right, with sky (0) in the top rows.
cv::Mat plane() {
  cv::Mat depth(60, 100, CV_32FC1);
  for (int y = 0; y < depth.rows; ++y)
    for (int x = 0; x < depth.cols; ++x) depth.at<float>(y, x) = y < 10 ? 0.0f : 10.0f + 0.1f * static_cast<float>(x);
  return depth;
}

MapPoint pointAt(int u, int v, double depth, bool edge) {
  MapPoint point;
  point.u = static_cast<float>(u);
  point.v = static_cast<float>(v);
  point.inverse_depth = 1.0 / depth;
  point.inverse_depth_variance = 1e-6 * point.inverse_depth * point.inverse_depth;
  point.observations = 1;
  point.class_mask = edge ? 1u : 0u;
  return point;
}

TEST(KeyframeDepthCheck, CountsWrongDepthsUpToTheMapScale) {
  const cv::Mat depth = plane();
  const double scale = 0.2;  // the map's units per metre
  std::vector<MapPoint> points;
  for (int u = 5; u < 95; u += 10) points.push_back(pointAt(u, 30, scale * (10.0 + 0.1 * u), true));  // 9 exact edges
  for (int u = 5; u < 95; u += 10) {
    const double wrong = u < 40 ? 2.0 : 1.0;  // 4 of 9 supportive points at twice their depth
    points.push_back(pointAt(u, 40, wrong * scale * (10.0 + 0.1 * u), false));
  }
  points.push_back(pointAt(50, 5, 3.0, true));  // on the sky: no true depth, not counted
  MapPoint unmeasured = pointAt(50, 30, 100.0, false);
  unmeasured.observations = 0;  // no depth yet: not counted
  points.push_back(unmeasured);

  const DepthCheck check = checkDepths(points, depth);
  EXPECT_NEAR(check.scale, scale, 1e-6);
  EXPECT_EQ(check.edges, 9);
  EXPECT_EQ(check.edges_wrong, 0);
  EXPECT_EQ(check.support, 9);
  EXPECT_EQ(check.support_wrong, 4);
  EXPECT_NEAR(check.supportWrongFraction(), 4.0 / 9.0, 1e-12);
  EXPECT_NEAR(check.median_error, 0.0, 1e-6);
}

TEST(KeyframeDepthCheck, AContourPointMayTakeEitherSide) {
  cv::Mat depth(20, 20, CV_32FC1, cv::Scalar(30.0f));
  depth.colRange(0, 10).setTo(10.0f);  // a near wall left of column 10, far background right of it
  // Reference points fix the scale at 1; the contour pixel (10) reads 30 m but sees 10 m on its left.
  std::vector<MapPoint> points = {pointAt(3, 5, 10.0, true), pointAt(16, 5, 30.0, true), pointAt(4, 8, 10.0, true),
                                  pointAt(10, 10, 10.0, true), pointAt(13, 10, 10.0, true)};
  const DepthCheck check = checkDepths(points, depth);
  EXPECT_NEAR(check.scale, 1.0, 1e-9);
  EXPECT_EQ(check.edges, 5);
  EXPECT_EQ(check.edges_wrong, 1);  // only the point three pixels inside the background
  EXPECT_EQ(checkDepths({}, depth).scale, 0.0);
}

}  // namespace
}  // namespace semantic_edge_vo
