#include "semantic_edge_vo/eval/keyframe_depth_check.h"

#include <algorithm>
#include <cmath>

#include "semantic_edge_vo/common/robust_statistics.h"

namespace semantic_edge_vo {
namespace {

/// A point with a depth, and the true depth at its pixel and around it.
struct Compared {
  const MapPoint* point;
  double estimate, truth, lowest, highest;
};

}  // namespace

DepthCheck checkDepths(const std::vector<MapPoint>& points, const cv::Mat& true_depth, double tolerance) {
  CV_Assert(true_depth.type() == CV_32FC1);
  std::vector<Compared> compared;
  std::vector<double> edge_ratios, all_ratios;
  for (const MapPoint& point : points) {
    if (!point.hasDepth()) continue;
    const int x = static_cast<int>(std::lround(point.u)), y = static_cast<int>(std::lround(point.v));
    if (x < 0 || y < 0 || x >= true_depth.cols || y >= true_depth.rows) continue;
    const double truth = true_depth.at<float>(y, x);
    if (!(truth > 0.0)) continue;
    double lowest = truth, highest = truth;
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        const int xx = std::clamp(x + dx, 0, true_depth.cols - 1), yy = std::clamp(y + dy, 0, true_depth.rows - 1);
        const double near = true_depth.at<float>(yy, xx);
        if (near > 0.0) lowest = std::min(lowest, near), highest = std::max(highest, near);
      }
    compared.push_back({&point, 1.0 / point.inverse_depth, truth, lowest, highest});
    all_ratios.push_back(compared.back().estimate / truth);
    if (point.isEdge()) edge_ratios.push_back(all_ratios.back());
  }
  DepthCheck check;
  if (compared.empty()) return check;
  check.scale = median(edge_ratios.empty() ? all_ratios : edge_ratios);
  std::vector<double> errors;
  for (const Compared& c : compared) {
    const double scaled = c.estimate / check.scale;
    errors.push_back(std::abs(scaled / c.truth - 1.0));
    const bool wrong = scaled < c.lowest / (1.0 + tolerance) || scaled > c.highest * (1.0 + tolerance);
    if (c.point->isEdge()) {
      ++check.edges;
      check.edges_wrong += wrong;
    } else {
      ++check.support;
      check.support_wrong += wrong;
    }
  }
  check.median_error = median(errors);
  return check;
}

}  // namespace semantic_edge_vo
