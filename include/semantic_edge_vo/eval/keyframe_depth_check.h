#pragma once
#include <vector>

#include <opencv2/core/mat.hpp>

#include "semantic_edge_vo/backend/map_point.h"

namespace semantic_edge_vo {

/// How a keyframe's point depths agree with a true depth map (synthetic sequences). Monocular depths
/// have an unknown scale, so each estimate is first divided by the median ratio of estimated to true
/// depth over the edge points (over all points when there are none: supportive points are the worse
/// measured, and a median over mostly wrong points would say nothing). A point is wrong when that
/// scaled depth lies below the lowest true depth around its pixel / (1 + tolerance) or above the
/// highest x (1 + tolerance) (3x3: a point on an occluding contour may belong to either side).
struct DepthCheck {
  int edges = 0, edges_wrong = 0;      ///< edge points with a depth and a true depth, and the wrong ones
  int support = 0, support_wrong = 0;  ///< the same for supportive points
  double scale = 0.0;                  ///< median of estimated / true depth, edges (0: nothing to compare)
  double median_error = 0.0;           ///< median of |scaled estimate / true depth - 1| at the pixel

  double edgesWrongFraction() const { return edges ? static_cast<double>(edges_wrong) / edges : 0.0; }
  double supportWrongFraction() const { return support ? static_cast<double>(support_wrong) / support : 0.0; }
};

constexpr double kDepthCheckTolerance = 0.2;

/// @param points       a keyframe's points; those without a depth (MapPoint::hasDepth) are skipped
/// @param true_depth   CV_32FC1 metres at each pixel of the keyframe's image, 0 where unknown (sky)
/// @param tolerance    relative, see above
DepthCheck checkDepths(const std::vector<MapPoint>& points, const cv::Mat& true_depth,
                       double tolerance = kDepthCheckTolerance);

}  // namespace semantic_edge_vo
