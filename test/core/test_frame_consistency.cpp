// A tracked frame agrees with the recent frames when its inlier ratio and its motion are close to theirs.
#include <gtest/gtest.h>

#include "semantic_edge_vo/frontend/frame_consistency.h"

namespace semantic_edge_vo {
namespace {

const Eigen::Vector3d kPredicted(0.0, 0.0, 1.0);  ///< one frame at 1 map unit a frame, straight ahead

FrameAgreement compare(double inlier_ratio, const Eigen::Vector3d& travel, double usual_travel = 1.0) {
  return compareWithRecentFrames(inlier_ratio, 0.8, 0.85, travel, kPredicted, usual_travel, FrameConsistencyOptions());
}

TEST(FrameConsistency, AMotionCloseToThePredictionAgrees) {
  const FrameAgreement agreement = compare(0.78, {0.05, 0.0, 1.1});
  EXPECT_TRUE(agreement.ok());
  EXPECT_NEAR(agreement.motion_deviation, std::hypot(0.05, 0.1), 1e-12);
}

TEST(FrameConsistency, ARepeatedFrameOrAJumpDisagrees) {
  EXPECT_FALSE(compare(0.9, Eigen::Vector3d::Zero()).motion_ok) << "no motion after a frame of travel: a repeated frame";
  EXPECT_FALSE(compare(0.9, {0.0, 0.0, 30.0}).motion_ok) << "thirty frames of travel at once";
  EXPECT_FALSE(compare(0.9, {0.45, 0.0, 0.9}).motion_ok) << "sideways by 25 degrees";
}

TEST(FrameConsistency, AFewInliersDisagree) {
  EXPECT_FALSE(compare(0.6, kPredicted).inliers_ok);
  EXPECT_TRUE(compare(0.7, kPredicted).inliers_ok);
}

TEST(FrameConsistency, NothingToCompareWithAgrees) {
  EXPECT_TRUE(compareWithRecentFrames(0.3, 0.0, 0.85, Eigen::Vector3d::Zero(), kPredicted, 0.0, FrameConsistencyOptions()).ok())
      << "no recent inlier ratio, no usual travel (the first frames of a map)";
}

TEST(FrameConsistency, OptionsAreValidated) {
  FrameConsistencyOptions options;
  EXPECT_EQ(options.validate(), "");
  options.max_motion_deviation = 0.0;
  EXPECT_NE(options.validate(), "");
}

}  // namespace
}  // namespace semantic_edge_vo
