#include <gtest/gtest.h>

#include "semantic_edge_vo/ros/conversions.h"

namespace semantic_edge_vo {
namespace {

TEST(Conversions, FieldSurvivesTheMessageWithoutCopies) {
  EdgeSet edges;
  edges.push_back(10.0f, 20.0f, 0.6f, 0.8f, 1.0f, 0b11u);
  edges.push_back(40.0f, 25.0f, -1.0f, 0.0f, 0.5f, 0b10u);
  FieldOptions options;
  options.pyramid_levels = 2;
  options.truncation_radius = 40.0f;  // the lookups below reach 28 px
  auto data = buildNearestNeighborField(edges.view(), 64, 48, {"a", "b"}, options);
  const float* seeds_before = data.levels[0].seed_u.data();
  NearestNeighborField msg;
  moveFieldInto(std::move(data), &msg);
  EXPECT_EQ(msg.levels[0].seed_u.data(), seeds_before) << "moved, not copied";

  std::string error;
  const NearestNeighborFieldView view = fieldView(msg, &error);
  ASSERT_EQ(error, "");
  ASSERT_EQ(view.validate(), "");
  EXPECT_EQ(view.levels[0].seed_u.data(), msg.levels[0].seed_u.data()) << "a view, not a copy";
  FieldMatch match;
  ASSERT_TRUE(view.nearest(0, 1, 38.0f, 25.0f, &match));
  EXPECT_EQ(match.edge, 1u);
  ASSERT_TRUE(view.nearest(0, 0, 38.0f, 25.0f, &match));
  EXPECT_EQ(match.edge, 0u);
}

TEST(Conversions, UnknownFieldKindIsAnError) {
  NearestNeighborField msg;
  msg.kind = "bogus";
  std::string error;
  fieldView(msg, &error);
  EXPECT_NE(error, "");
}

TEST(Conversions, CameraFromInfoAndPoseRoundTrip) {
  sensor_msgs::CameraInfo info;
  info.width = 1241;
  info.height = 376;
  info.K = {718.856, 0, 607.19, 0, 718.856, 185.22, 0, 0, 1};
  const PinholeCamera camera = cameraFromInfo(info);
  EXPECT_EQ(camera.validate(), "");
  EXPECT_DOUBLE_EQ(camera.cx, 607.19);
  info.K.fill(0.0);
  EXPECT_NE(cameraFromInfo(info).validate(), "");

  // A rectified image (image_proc): its intrinsics are P's, not the raw camera's K.
  info.K = {700.0, 0, 620.0, 0, 702.0, 180.0, 0, 0, 1};
  info.P = {690.0, 0, 615.5, 0, 0, 690.0, 183.25, 0, 0, 0, 1, 0};
  const PinholeCamera rectified = cameraFromInfo(info);
  EXPECT_DOUBLE_EQ(rectified.fx, 690.0);
  EXPECT_DOUBLE_EQ(rectified.fy, 690.0);
  EXPECT_DOUBLE_EQ(rectified.cx, 615.5);
  EXPECT_DOUBLE_EQ(rectified.cy, 183.25);

  // A 2x2-binned region of interest of that sensor: REP-104 scales and shifts the intrinsics
  // (as image_geometry's camera model), and the image is the region's size over the binning.
  info.binning_x = info.binning_y = 2;
  info.roi.x_offset = 100;
  info.roi.y_offset = 40;
  info.roi.width = 1000;
  info.roi.height = 300;
  const PinholeCamera binned = cameraFromInfo(info);
  EXPECT_DOUBLE_EQ(binned.fx, 345.0);
  EXPECT_DOUBLE_EQ(binned.fy, 345.0);
  EXPECT_DOUBLE_EQ(binned.cx, (615.5 - 100.0) / 2.0);
  EXPECT_DOUBLE_EQ(binned.cy, (183.25 - 40.0) / 2.0);
  EXPECT_EQ(binned.width, 500);
  EXPECT_EQ(binned.height, 150);
  info.roi = sensor_msgs::RegionOfInterest();  // binning alone: the whole sensor, halved
  info.binning_y = 0;                          // 0 is "no binning", as 1
  const PinholeCamera halved = cameraFromInfo(info);
  EXPECT_EQ(halved.width, 620);
  EXPECT_EQ(halved.height, 376);
  EXPECT_DOUBLE_EQ(halved.cx, 615.5 / 2.0);
  EXPECT_DOUBLE_EQ(halved.fy, 690.0);

  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.rotate(Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 2, 3).normalized()));
  pose.translation() << 1, -2, 3;
  EXPECT_TRUE(fromPoseMsg(toPoseMsg(pose)).isApprox(pose, 1e-12));
}

}  // namespace
}  // namespace semantic_edge_vo
