#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include <opencv2/imgproc.hpp>

#include "semantic_edge_vo/two_view_initializer.h"

namespace semantic_edge_vo {
namespace {

// A forward drive past a truck that overtakes close by on the right: ground (y = 1.6 m below the
// camera) and a wall 60 m ahead stand still; the truck's side (the plane x = 2.5 m, 3.5 m tall,
// 40 m long, its rear beside the camera at first) drives 0.8 m a frame while the camera drives 0.5,
// so against the truck the camera backs up. Each surface is painted with the same blurred noise, looked up by its own coordinates.
constexpr double kCameraStep = 0.5, kTruckStep = 0.8;

cv::Mat noiseTexture() {
  cv::Mat texture(512, 512, CV_32FC1);
  cv::RNG rng(7);
  rng.fill(texture, cv::RNG::UNIFORM, 0.0, 255.0);
  cv::GaussianBlur(texture, texture, cv::Size(0, 0), 2.0);
  cv::normalize(texture, texture, 20.0, 235.0, cv::NORM_MINMAX);
  return texture;
}

double lookUp(const cv::Mat& texture, double a, double b) {
  const double texels_per_metre = 40.0;
  const int i = static_cast<int>(std::floor(a * texels_per_metre)) & 511, j = static_cast<int>(std::floor(b * texels_per_metre)) & 511;
  return texture.at<float>(j, i);
}

cv::Mat renderOvertakingTruck(const PinholeCamera& camera, const cv::Mat& texture, int frame) {
  cv::Mat gray(camera.height, camera.width, CV_8UC1);
  const double camera_z = kCameraStep * frame, truck_rear = -10.0 + kTruckStep * frame;
  for (int v = 0; v < camera.height; ++v) {
    for (int u = 0; u < camera.width; ++u) {
      const Eigen::Vector3d ray = camera.backProject(u, v, 1.0);
      double nearest = (60.0 - camera_z) / ray.z(), value = lookUp(texture, ray.x() * nearest, ray.y() * nearest);
      if (ray.y() > 0.0 && 1.6 / ray.y() < nearest) {
        nearest = 1.6 / ray.y();
        value = lookUp(texture, ray.x() * nearest, camera_z + nearest);
      }
      if (ray.x() > 0.0 && 2.5 / ray.x() < nearest) {
        const double t = 2.5 / ray.x(), along = camera_z + t - truck_rear, up = ray.y() * t;
        if (along >= 0.0 && along <= 40.0 && up >= -1.9 && up <= 1.6) value = lookUp(texture, along, up) * 0.8 + 40.0;
      }
      gray.at<std::uint8_t>(v, u) = cv::saturate_cast<std::uint8_t>(value);
    }
  }
  return gray;
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
  const cv::Mat texture = noiseTexture();
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
