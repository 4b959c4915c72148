#include <gtest/gtest.h>

#include "semantic_edge_vo/ros/frame_pairing.h"
#include "stamped_messages.h"

namespace semantic_edge_vo {
namespace {

const sensor_msgs::CameraInfoConstPtr kInfo = boost::make_shared<sensor_msgs::CameraInfo>();

TEST(FramePairing, PairsByStampInEitherOrderAndReleasesInStampOrder) {
  FramePairing pairing(false, 0.5, 10);
  const ros::WallTime t0(100.0);
  EXPECT_TRUE(pairing.addImage(imageAt(1.0), kInfo, t0).empty()) << "waits for its class map";
  EXPECT_TRUE(pairing.addClasses(imageAt(2.0), t0).empty()) << "a class map waits for its image";
  auto ready = pairing.addClasses(imageAt(1.0), t0 + ros::WallDuration(0.1));
  ASSERT_EQ(ready.size(), 1u);
  EXPECT_TRUE(ready[0].complete);
  EXPECT_EQ(ready[0].image->header.stamp, ros::Time(1.0));
  ready = pairing.addImage(imageAt(2.0), kInfo, t0 + ros::WallDuration(0.2));
  ASSERT_EQ(ready.size(), 1u);
  EXPECT_TRUE(ready[0].complete);
  EXPECT_EQ(pairing.pending(), 0u);

  // Image 3 never gets classes; image 4 does: 3 leaves first, incomplete.
  pairing.addImage(imageAt(3.0), kInfo, t0);
  pairing.addImage(imageAt(4.0), kInfo, t0);
  ready = pairing.addClasses(imageAt(4.0), t0);
  ASSERT_EQ(ready.size(), 2u);
  EXPECT_FALSE(ready[0].complete);
  EXPECT_EQ(ready[0].image->header.stamp, ros::Time(3.0));
  EXPECT_TRUE(ready[1].complete);
}

TEST(FramePairing, LateInputsExpireAndEdgeMapsAreAwaited) {
  FramePairing pairing(true, 0.5, 2);
  const ros::WallTime t0(100.0);
  pairing.addImage(imageAt(1.0), kInfo, t0);
  EXPECT_TRUE(pairing.addClasses(imageAt(1.0), t0).empty()) << "still waits for the edge map";
  EXPECT_TRUE(pairing.expire(t0 + ros::WallDuration(0.4)).empty());
  auto ready = pairing.expire(t0 + ros::WallDuration(0.6));
  ASSERT_EQ(ready.size(), 1u);
  EXPECT_FALSE(ready[0].complete);
  EXPECT_TRUE(ready[0].classes) << "what did arrive comes along";

  pairing.addClasses(imageAt(5.0), t0);  // a lone class map expires silently
  EXPECT_TRUE(pairing.expire(t0 + ros::WallDuration(1.0)).empty());
  EXPECT_EQ(pairing.pending(), 0u);

  // Bounded: a third waiting stamp pushes the oldest out.
  pairing.addImage(imageAt(6.0), kInfo, t0);
  pairing.addImage(imageAt(7.0), kInfo, t0);
  ready = pairing.addImage(imageAt(8.0), kInfo, t0);
  ASSERT_EQ(ready.size(), 1u);
  EXPECT_EQ(ready[0].image->header.stamp, ros::Time(6.0));
}

TEST(FramePairing, ClearDropsWhatWaitsAndCountsTheImages) {
  FramePairing pairing(false, 0.5, 10);
  const ros::WallTime t0(100.0);
  pairing.addImage(imageAt(1.0), kInfo, t0);
  pairing.addImage(imageAt(2.0), kInfo, t0);
  pairing.addClasses(imageAt(3.0), t0);  // a lone map: not an image
  EXPECT_EQ(pairing.clear(), 2u);
  EXPECT_EQ(pairing.pending(), 0u);
  // An earlier stamp pairs afresh, without the dropped ones coming out after it.
  pairing.addImage(imageAt(0.5), kInfo, t0);
  const auto ready = pairing.addClasses(imageAt(0.5), t0);
  ASSERT_EQ(ready.size(), 1u);
  EXPECT_TRUE(ready[0].complete);
  EXPECT_TRUE(pairing.expire(t0 + ros::WallDuration(1.0)).empty());
}

}  // namespace
}  // namespace semantic_edge_vo
