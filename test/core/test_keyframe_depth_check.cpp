#include <algorithm>
#include <filesystem>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "semantic_edge_vo/eval/keyframe_depth_check.h"
#include "semantic_edge_vo/eval/keyframe_depth_report.h"
#include "semantic_edge_vo/synthetic/sequence_formats.h"

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

TEST(KeyframeDepthCheck, TheEdgesSetTheScale) {
  // Five of eight points are supportive at twice their depth: a median over all points would take
  // their scale and call the exact edges wrong.
  const cv::Mat depth = plane();
  std::vector<MapPoint> points;
  for (int u : {20, 50, 80}) points.push_back(pointAt(u, 30, 10.0 + 0.1 * u, true));
  for (int u : {10, 30, 40, 60, 70}) points.push_back(pointAt(u, 40, 2.0 * (10.0 + 0.1 * u), false));
  const DepthCheck check = checkDepths(points, depth);
  EXPECT_NEAR(check.scale, 1.0, 1e-6);
  EXPECT_EQ(check.edges_wrong, 0);
  EXPECT_EQ(check.support_wrong, 5);
  // Without edges, the supportive points set it (and then agree with themselves).
  points.erase(points.begin(), points.begin() + 3);
  EXPECT_NEAR(checkDepths(points, depth).scale, 2.0, 1e-6);
  EXPECT_EQ(checkDepths(points, depth).support_wrong, 0);
}

/// A keyframe of frame `index` whose image is `width` x 60, with points on the plane at map scale 1.
std::shared_ptr<Keyframe> keyframeOf(int index, int width = 100) {
  auto frame = std::make_shared<OdometryFrame>();
  frame->index = index;
  PinholeCamera camera;
  camera.fx = camera.fy = 50.0;
  camera.cx = 0.5 * width;
  camera.cy = 30.0;
  camera.width = width;
  camera.height = 60;
  frame->pyramid = std::make_shared<ImagePyramid>(cv::Mat(60, width, CV_8UC1, cv::Scalar(0)), camera, 1);
  auto keyframe = std::make_shared<Keyframe>();
  keyframe->id = index;
  keyframe->frame = frame;
  for (int u = 5; u < 95; u += 10) keyframe->points.push_back(pointAt(u, 30, 10.0 + 0.1 * u, true));
  return keyframe;
}

TEST(KeyframeDepthReport, ChecksEachKeyframeWhenNewAndWhenRetired) {
  const std::filesystem::path folder = std::filesystem::temp_directory_path() / "sevo_keyframe_depth_report";
  std::filesystem::remove_all(folder);
  std::filesystem::create_directories(folder);
  for (const char* name : {"000003.png", "000007.png"})
    ASSERT_TRUE(cv::imwrite((folder / name).string(), synthetic::encodeDepth(plane())));
  ASSERT_TRUE(cv::imwrite((folder / "000008.png").string(), synthetic::encodeDepth(cv::Mat(60, 50, CV_32FC1, cv::Scalar(5.0f)))));

  KeyframeDepthReport report(folder.string());
  const std::shared_ptr<const Keyframe> first = keyframeOf(3);
  EXPECT_EQ(report.update(first, {}), "");
  EXPECT_EQ(report.update(first, {}), "");  // no new keyframe: nothing checked
  auto second = keyframeOf(7);
  second->points[0].inverse_depth *= 3.0;  // one point three times too near
  // The window the second keyframe made holds the first as that window left it: retired from there.
  auto settled_first = std::make_shared<Keyframe>(*first);
  settled_first->points[1].inverse_depth *= 3.0;
  auto window = std::make_shared<KeyframeWindow>();
  window->frame_index = 7;
  window->keyframes = {settled_first, second};
  EXPECT_EQ(report.update(second, {window}), "");
  report.finish(second);
  report.finish(second);  // nothing left to retire
  // Rows in order: frame, stage, edges, wrong edges, supportive, wrong supportive, scale (1), ...
  const std::string table = report.table();
  std::size_t at = 0;
  for (const char* row : {"\n3 new 9 0 0 0 1 ", "\n3 retired 9 1 0 0 1 ", "\n7 new 9 1 0 0 1 ", "\n7 retired 9 1 0 0 1 "}) {
    at = table.find(row, at);
    ASSERT_NE(at, std::string::npos) << row << " in\n" << table;
  }
  EXPECT_EQ(std::count(table.begin(), table.end(), '\n'), 3 + 4) << table;  // 3 header lines, 4 checks
  EXPECT_NE(report.summary().find("new 2: 11 % of edge"), std::string::npos) << report.summary();

  KeyframeDepthReport missing(folder.string());
  EXPECT_NE(missing.update(keyframeOf(9), {}).find("000009.png: no such depth file"), std::string::npos);
  KeyframeDepthReport other_size(folder.string());
  EXPECT_NE(other_size.update(keyframeOf(8), {}).find("50x60, the images are 100x60"), std::string::npos);
  std::filesystem::remove_all(folder);
}

}  // namespace
}  // namespace semantic_edge_vo
