#include <gtest/gtest.h>

#include "semantic_edge_vo/ros/stamp_order.h"

namespace semantic_edge_vo {
namespace {

using Verdict = StampOrder::Verdict;

TEST(StampOrder, RefusesSmallStepsBackAndRestartsOnAJumpBack) {
  StampOrder order(1.0);
  EXPECT_EQ(order.accept(ros::Time(100.0)), Verdict::kNext) << "the first stamp";
  EXPECT_EQ(order.accept(ros::Time(100.1)), Verdict::kNext);
  EXPECT_EQ(order.accept(ros::Time(100.1)), Verdict::kNotIncreasing) << "a repeated stamp";
  EXPECT_EQ(order.accept(ros::Time(99.2)), Verdict::kNotIncreasing) << "0.9 s back: a reordered frame";
  EXPECT_EQ(order.last(), ros::Time(100.1)) << "a refused stamp is not the last one";
  EXPECT_EQ(order.accept(ros::Time(100.2)), Verdict::kNext);
  EXPECT_EQ(order.accept(ros::Time(10.0)), Verdict::kRestart) << "90 s back: the bag played again";
  EXPECT_EQ(order.last(), ros::Time(10.0));
  EXPECT_EQ(order.accept(ros::Time(10.1)), Verdict::kNext) << "the new pass goes on from its own stamps";
}

TEST(StampOrder, WithoutAToleranceAnyStepBackIsARestart) {
  StampOrder order(0.0);
  EXPECT_EQ(order.accept(ros::Time(5.0)), Verdict::kNext);
  EXPECT_EQ(order.accept(ros::Time(5.0)), Verdict::kNotIncreasing);
  EXPECT_EQ(order.accept(ros::Time(4.999)), Verdict::kRestart);
}

TEST(StampOrder, TheFirstStampMayBeZero) {
  StampOrder order(1.0);
  EXPECT_EQ(order.accept(ros::Time(0.0)), Verdict::kNext);
  EXPECT_EQ(order.accept(ros::Time(0.0)), Verdict::kNotIncreasing);
}

}  // namespace
}  // namespace semantic_edge_vo
