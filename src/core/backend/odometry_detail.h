#pragma once
// Helpers shared by the files that implement Odometry (odometry*.cpp); not part of the API.
#include <chrono>
#include <memory>

#include <opencv2/core/mat.hpp>

#include "semantic_edge_vo/backend/odometry.h"

namespace semantic_edge_vo {
namespace odometry_detail {

inline double elapsedMs(std::chrono::steady_clock::time_point since) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - since).count();
}

/// The frame's full-resolution image, 8 bits (KLT, the two-view initialisation).
cv::Mat gray8(const OdometryFrame& frame);

/// The layers the frame's edges are matched in: a frame without classes, in the all-edges layer.
inline EdgeLayers edgeLayersOf(const OdometryFrame& frame) { return frame.classes_known ? EdgeLayers::kOwn : EdgeLayers::kAllEdges; }

}  // namespace odometry_detail
}  // namespace semantic_edge_vo
