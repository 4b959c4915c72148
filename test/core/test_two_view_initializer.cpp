#include <gtest/gtest.h>

#include "semantic_edge_vo/two_view_initializer.h"

namespace semantic_edge_vo {
namespace {

TEST(TwoViewInitializer, AFrameWithoutPointsFailsInsteadOfThrowing) {
  // A frame whose candidates were all left out (all of it movable, say): nothing to follow.
  PinholeCamera camera = kittiCamera();
  const cv::Mat gray(camera.height, camera.width, CV_8UC1, cv::Scalar(90));
  TwoViewInitializer initializer(InitializerOptions(), camera);
  initializer.reset(gray, {});
  TwoViewInitializer::Status status = TwoViewInitializer::Status::kReady;
  EXPECT_NO_THROW(status = initializer.add(gray));
  EXPECT_EQ(status, TwoViewInitializer::Status::kFailed);
}

}  // namespace
}  // namespace semantic_edge_vo
