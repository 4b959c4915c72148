#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "semantic_edge_vo/backend/two_view_initializer.h"
#include "truck_scene.h"

namespace semantic_edge_vo {
namespace {

// The truck overtakes: it drives 0.8 m a frame while the camera drives 0.5, so against the truck
// the camera backs up.
constexpr double kCameraStep = 0.5, kTruckStep = 0.8;

cv::Mat renderOvertakingTruck(const PinholeCamera& camera, const cv::Mat& texture, int frame) {
  return testing_scenes::renderTruckScene(camera, texture, kCameraStep * frame, -10.0 + kTruckStep * frame).gray;
}

// The truck is the larger consensus: a denser grid of pixels on the right half of the image.
std::vector<Eigen::Vector2f> candidatePixels(const PinholeCamera& camera) {
  std::vector<Eigen::Vector2f> pixels;
  for (int v = 20; v < camera.height - 20; v += 6)
    for (int u = 20; u < camera.width - 20; u += (u < camera.width / 2 ? 18 : 6)) pixels.emplace_back(u, v);
  return pixels;
}

// Initialises on the drive; the last camera's travel direction in the first frame, NaN on failure.
Eigen::Vector3d initialTravel(const Eigen::Vector3d& expected_travel) {
  const PinholeCamera camera = kittiCamera();
  const cv::Mat texture = testing_scenes::noiseTexture();
  InitializerOptions options;
  options.min_parallax = 0.01;
  TwoViewInitializer initializer(options, camera);
  initializer.reset(renderOvertakingTruck(camera, texture, 0), candidatePixels(camera), expected_travel);
  for (int frame = 1; frame <= options.max_frames; ++frame) {
    const TwoViewInitializer::Status status = initializer.add(renderOvertakingTruck(camera, texture, frame));
    if (status == TwoViewInitializer::Status::kFailed) break;
    if (status == TwoViewInitializer::Status::kReady) {
      const Eigen::Isometry3d& T = initializer.T_last_first();
      return (-(T.linear().transpose() * T.translation())).normalized();
    }
  }
  return Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
}

TEST(TwoViewInitializer, ATruckOvertakingCloseByIsNotTakenForTheCarsTravel) {
  // Without a travel to keep to, the largest consensus wins: the truck's, the camera backing up.
  const Eigen::Vector3d unconstrained = initialTravel(Eigen::Vector3d::Zero());
  ASSERT_TRUE(unconstrained.allFinite());
  EXPECT_LT(unconstrained.z(), 0.0) << unconstrained.transpose();
  // Re-initialising after a loss, the car still drives forward: the rest, the road and the wall.
  const Eigen::Vector3d kept = initialTravel(Eigen::Vector3d::UnitZ());
  ASSERT_TRUE(kept.allFinite());
  EXPECT_GT(kept.z(), std::cos(5.0 * M_PI / 180.0)) << kept.transpose();
}

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
