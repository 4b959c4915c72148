#pragma once
// Helpers shared by the files that implement Odometry (odometry*.cpp); not part of the API.
#include <chrono>
#include <memory>
#include <vector>

#include <opencv2/core/mat.hpp>

#include "semantic_edge_vo/backend/odometry.h"

namespace semantic_edge_vo {
namespace odometry_detail {

inline double elapsedMs(std::chrono::steady_clock::time_point since) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - since).count();
}

/// The frame's full-resolution image, 8 bits (KLT, the two-view initialisation).
cv::Mat gray8(const OdometryFrame& frame);

/// A measured inverse depth at a pixel of the keyframe that receives it.
struct DepthSample {
  Eigen::Vector2d pixel;
  double inverse_depth;
};

/// Points without a measurement take the median of the samples within `radius` (bucketed), or of
/// all samples, as a prior with a wide variance; the epipolar search then measures them.
void propagateDepths(const std::vector<DepthSample>& samples, const PinholeCamera& camera, double radius,
                     double default_inverse_depth, std::vector<MapPoint>* points);

}  // namespace odometry_detail
}  // namespace semantic_edge_vo
