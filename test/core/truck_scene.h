#pragma once
// Test fixture: a forward drive past a truck close by on the right. Ground (y = 1.6 m below the
// camera) and a wall 60 m ahead stand still; the truck's side is the plane x = 2.5 m, 3.5 m tall,
// 40 m long. Each surface is painted with the same blurred noise, looked up by its own coordinates.
#include <cmath>
#include <cstdint>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "semantic_edge_vo/common/camera.h"

namespace semantic_edge_vo {
namespace testing_scenes {

inline cv::Mat noiseTexture() {
  cv::Mat texture(512, 512, CV_32FC1);
  cv::RNG rng(7);
  rng.fill(texture, cv::RNG::UNIFORM, 0.0, 255.0);
  cv::GaussianBlur(texture, texture, cv::Size(0, 0), 2.0);
  cv::normalize(texture, texture, 20.0, 235.0, cv::NORM_MINMAX);
  return texture;
}

inline double lookUp(const cv::Mat& texture, double a, double b) {
  const double texels_per_metre = 40.0;
  const int i = static_cast<int>(std::floor(a * texels_per_metre)) & 511, j = static_cast<int>(std::floor(b * texels_per_metre)) & 511;
  return texture.at<float>(j, i);
}

/// What the camera sees of the scene.
struct TruckView {
  cv::Mat gray;
  cv::Mat depth;     ///< CV_32FC1, metres along the optical axis
  cv::Mat on_truck;  ///< CV_8UC1, 255 where the truck is seen
};

/// The view of a camera at z = camera_z (looking along +z) with the truck's rear at z = truck_rear.
inline TruckView renderTruckScene(const PinholeCamera& camera, const cv::Mat& texture, double camera_z, double truck_rear) {
  TruckView view{cv::Mat(camera.height, camera.width, CV_8UC1), cv::Mat(camera.height, camera.width, CV_32FC1),
                 cv::Mat::zeros(camera.height, camera.width, CV_8UC1)};
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
        if (along >= 0.0 && along <= 40.0 && up >= -1.9 && up <= 1.6) {
          value = lookUp(texture, along, up) * 0.8 + 40.0;
          nearest = t;
          view.on_truck.at<std::uint8_t>(v, u) = 255;
        }
      }
      view.gray.at<std::uint8_t>(v, u) = cv::saturate_cast<std::uint8_t>(value);
      view.depth.at<float>(v, u) = static_cast<float>(nearest);
    }
  }
  return view;
}

}  // namespace testing_scenes
}  // namespace semantic_edge_vo
