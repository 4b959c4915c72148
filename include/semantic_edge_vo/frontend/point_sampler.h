#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include <opencv2/core/mat.hpp>

#include "semantic_edge_vo/common/edge_set.h"

namespace semantic_edge_vo {

struct PointSamplerOptions {
  int max_edge_points = 3000;      ///< N: edge pixels sampled for the odometry
  int min_support_points = 1000;   ///< M: unlabeled supportive pixels always sampled (when available)
  int support_block_size = 32;     ///< block side for the adaptive gradient threshold, pixels
  double support_threshold_offset = 7.0;  ///< added to the block's median gradient magnitude (DSO's setting_minGradHistAdd)
  int support_min_distance = 2;    ///< supportive pixels keep this far from edge pixels, pixels

  std::string validate() const;
};

struct PointSample {
  std::vector<std::uint32_t> edge_indices;  ///< into the EdgeSet
  std::vector<float> support_u, support_v;  ///< supportive pixels, full-resolution pixels
};

/// Picks a spatially well-spread sample of edge pixels (strongest first, round-robin over a grid so
/// every region gets its share) and DSO-style supportive pixels (block-wise adaptive gradient
/// thresholds), taking more supportive pixels where edges are scarce: the edge shortfall below N is
/// added to M.
class PointSampler {
 public:
  explicit PointSampler(const PointSamplerOptions& options) : options_(options) {}

  /// @param[in] gray 8-bit image the edges come from
  PointSample sample(const cv::Mat& gray, const EdgeSetView& edges) const;

 private:
  std::vector<std::uint32_t> sampleEdges(const EdgeSetView& edges, int width, int height) const;
  void sampleSupport(const cv::Mat& gray, const EdgeSetView& edges, int count, PointSample* sample) const;

  PointSamplerOptions options_;
};

}  // namespace semantic_edge_vo
