#include <cmath>
#include <memory>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>

#include "semantic_edge_vo/backend/keyframe_depths.h"
#include "semantic_edge_vo/frontend/image_pyramid.h"

namespace semantic_edge_vo {
namespace {

std::shared_ptr<const OdometryFrame> texturedFrame(const PinholeCamera& camera, int index) {
  cv::Mat gray(camera.height, camera.width, CV_8UC1);
  cv::randu(gray, 0, 255);
  auto frame = std::make_shared<OdometryFrame>();
  frame->index = index;
  frame->pyramid = std::make_shared<const ImagePyramid>(gray, camera, 1);
  return frame;
}

MapPoint candidateAt(double u, double v) {
  MapPoint point;
  point.u = static_cast<float>(u);
  point.v = static_cast<float>(v);
  return point;
}

TEST(KeyframeDepths, MapDepthsAreThePreviousKeyframesMeasuredPointsSeenFromTheNewOne) {
  const PinholeCamera camera = kittiCamera();
  Keyframe previous;
  previous.frame = texturedFrame(camera, 0);
  MapPoint measured = candidateAt(800.0, 250.0);
  measured.inverse_depth = 0.1;  // 10 m
  measured.inverse_depth_variance = std::pow(0.05 * measured.inverse_depth, 2);
  measured.observations = 4;
  previous.points = {measured};

  Keyframe next;  // 2 m forward: the point is 8 m away, farther from the centre
  next.T_world_cam.translation() = Eigen::Vector3d(0.0, 0.0, 2.0);
  next.frame = texturedFrame(camera, 1);
  const Eigen::Vector3d seen = next.T_world_cam.inverse() * camera.backProject(800.0, 250.0, 10.0);
  const Eigen::Vector2d pixel = camera.project(seen);
  next.points = {candidateAt(pixel.x() + 1.5, pixel.y()), candidateAt(pixel.x() + 6.0, pixel.y()), candidateAt(200.0, 100.0)};

  std::vector<MapPoint> map_depths;
  KeyframeDepths(EpipolarSearchOptions{}, camera, 30.0, 0.1).triangulate(&next, previous, &map_depths);

  ASSERT_EQ(map_depths.size(), 3u);
  ASSERT_TRUE(map_depths[0].hasDepth()) << "1.5 px from where the map's point falls";
  EXPECT_NEAR(map_depths[0].inverse_depth, 1.0 / 8.0, 1e-9);
  EXPECT_NEAR(std::sqrt(map_depths[0].inverse_depth_variance) / map_depths[0].inverse_depth, 0.05, 1e-9);
  EXPECT_EQ(map_depths[0].observations, 1);
  EXPECT_FALSE(map_depths[1].hasDepth()) << "6 px away: another surface may be there";
  EXPECT_FALSE(map_depths[2].hasDepth()) << "no map point near";
  EXPECT_EQ(map_depths[1].inverse_depth, 0.0);
}

}  // namespace
}  // namespace semantic_edge_vo
