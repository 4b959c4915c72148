#include <gtest/gtest.h>

#include "semantic_edge_vo/frontend/motion_model.h"

namespace semantic_edge_vo {
namespace {

Eigen::Isometry3d forward(double z) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation().z() = z;
  return pose;
}

TEST(MotionModel, PredictsAtConstantVelocityOverTheFramesADroppedStreamSkipped) {
  MotionModel model;
  for (int i = 0; i < 4; ++i) model.remember(forward(1.0 * i), {i, 0.1 * i}, true);
  EXPECT_NEAR(model.predict({4, 0.4}).translation().z(), 4.0, 1e-9);
  // Frames 4 and 5 were dropped: by the stamps, three intervals pass.
  EXPECT_DOUBLE_EQ(model.framesBetween(model.lastStamp(), {6, 0.6}), 3.0);
  EXPECT_NEAR(model.predict({6, 0.6}).translation().z(), 6.0, 1e-9);
  EXPECT_NEAR(model.drivingMotion().head<3>().norm(), 1.0, 1e-9);
}

TEST(MotionModel, AStandingCarIsAlsoGuessedToDriveOffAndDeadReckoningEnds) {
  MotionModel model;
  for (int i = 0; i < 5; ++i) model.remember(forward(1.0 * i), {i, 0.1 * i}, true);
  for (int i = 5; i < 8; ++i) model.remember(forward(4.0), {i, 0.1 * i}, true);  // stopped
  const std::vector<Eigen::Isometry3d> guesses = model.guesses({8, 0.8});
  ASSERT_EQ(guesses.size(), 5u);
  EXPECT_NEAR(guesses.back().translation().z(), 5.0, 1e-9);  // one frame's driving travel
  // Untrusted predictions beyond kMaxDeadReckoning frames stop moving.
  MotionModel lost;
  for (int i = 0; i < 3; ++i) lost.remember(forward(1.0 * i), {i, 0.1 * i}, true);
  for (int i = 3; i < 3 + MotionModel::kMaxDeadReckoning; ++i) lost.remember(lost.predict({i, 0.1 * i}), {i, 0.1 * i}, false);
  const int next = 3 + MotionModel::kMaxDeadReckoning;
  EXPECT_DOUBLE_EQ(lost.framesToExtrapolate({next, 0.1 * next}), 0.0);
}

TEST(MotionModel, TheTrackedVelocityLeavesOutTheWindowsCorrectionOfTheLastPose) {
  MotionModel model;
  for (int i = 0; i < 3; ++i) model.remember(forward(1.0 * i), {i, 0.1 * i}, true);
  // Frame 3 was tracked at z = 3; the window then moved it (a keyframe) by 0.4 along z.
  const Eigen::Isometry3d correction = forward(0.4);
  model.remember(correction * forward(3.0), {3, 0.3}, true, correction);
  EXPECT_NEAR(model.predict({4, 0.4}).translation().z(), 4.8, 1e-9) << "the prediction repeats the correction";
  EXPECT_NEAR(model.predictAtTrackedVelocity({4, 0.4}).translation().z(), 4.4, 1e-9) << "one frame's travel from the moved pose";
  // The next pose has no correction of its own: both predictions agree again.
  model.remember(forward(4.4), {4, 0.4}, true);
  EXPECT_NEAR(model.predict({5, 0.5}).translation().z(), model.predictAtTrackedVelocity({5, 0.5}).translation().z(), 1e-12);
}

}  // namespace
}  // namespace semantic_edge_vo
