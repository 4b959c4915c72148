#include <gtest/gtest.h>

#include "semantic_edge_vo/ros/camera_info_pairing.h"
#include "stamped_messages.h"

namespace semantic_edge_vo {
namespace {

sensor_msgs::CameraInfoConstPtr infoAt(double stamp) { return stampedAt<sensor_msgs::CameraInfo>(stamp); }

TEST(CameraInfoPairing, TakesTheNearestCameraInfoWithinTheTolerance) {
  CameraInfoPairing pairing(0.005, 0.5, 5);
  const ros::WallTime t0(100.0);
  EXPECT_TRUE(pairing.addInfo(infoAt(1.000), t0).empty());
  EXPECT_TRUE(pairing.addInfo(infoAt(1.100), t0).empty());
  auto pairs = pairing.addImage(imageAt(1.003), t0);  // 3 ms after its camera_info
  ASSERT_EQ(pairs.size(), 1u);
  ASSERT_TRUE(pairs[0].info);
  EXPECT_EQ(pairs[0].info->header.stamp, ros::Time(1.000));
  // 10 ms from the nearest: outside the tolerance, it waits.
  EXPECT_TRUE(pairing.addImage(imageAt(1.090), t0).empty());
  EXPECT_EQ(pairing.waiting(), 1u);
}

TEST(CameraInfoPairing, AnImageWaitsForALateCameraInfoAndOrderIsKept) {
  CameraInfoPairing pairing(0.0, 0.5, 5);
  const ros::WallTime t0(100.0);
  EXPECT_TRUE(pairing.addImage(imageAt(1.0), t0).empty());
  EXPECT_TRUE(pairing.addImage(imageAt(1.1), t0).empty());
  // Image 1.1's camera_info comes first: image 1.0 still leaves before it (once 1.0's comes).
  EXPECT_TRUE(pairing.addInfo(infoAt(1.1), t0).empty());
  const auto pairs = pairing.addInfo(infoAt(1.0), t0);
  ASSERT_EQ(pairs.size(), 2u);
  EXPECT_EQ(pairs[0].image->header.stamp, ros::Time(1.0));
  EXPECT_EQ(pairs[1].image->header.stamp, ros::Time(1.1));
  EXPECT_EQ(pairs[1].info->header.stamp, ros::Time(1.1));
}

TEST(CameraInfoPairing, WithoutACameraInfoAnImageLeavesEmptyHandedAfterTheWait) {
  CameraInfoPairing pairing(0.005, 0.5, 3);
  const ros::WallTime t0(100.0);
  EXPECT_TRUE(pairing.addImage(imageAt(1.0), t0).empty());
  EXPECT_TRUE(pairing.expire(t0 + ros::WallDuration(0.4)).empty());
  auto pairs = pairing.expire(t0 + ros::WallDuration(0.6));
  ASSERT_EQ(pairs.size(), 1u);
  EXPECT_FALSE(pairs[0].info);
  // A full queue lets its oldest go at once.
  for (double stamp : {2.0, 2.1, 2.2}) EXPECT_TRUE(pairing.addImage(imageAt(stamp), t0).empty());
  pairs = pairing.addImage(imageAt(2.3), t0);
  ASSERT_EQ(pairs.size(), 1u);
  EXPECT_EQ(pairs[0].image->header.stamp, ros::Time(2.0));
  EXPECT_EQ(pairing.waiting(), 3u);
}

}  // namespace
}  // namespace semantic_edge_vo
