#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include <opencv2/core/mat.hpp>

#include "semantic_edge_vo/class_evidence.h"
#include "semantic_edge_vo/edge_set.h"

namespace semantic_edge_vo {

struct PointSamplerOptions {
  int max_edge_points = 3000;      ///< N: edge pixels sampled for the odometry
  int min_support_points = 1000;   ///< M: unlabeled supportive pixels always sampled (when available)
  int support_block_size = 32;     ///< block side for the adaptive gradient threshold, pixels
  double support_threshold_offset = 7.0;  ///< added to the block's median gradient magnitude (DSO's setting_minGradHistAdd)
  int support_min_distance = 2;    ///< supportive pixels keep this far from edge pixels, pixels
  /// Classes whose points are not sampled when class evidence is at hand (comma-separated names;
  /// names missing from the class table are ignored). A vehicle driving along the road moves like
  /// static structure at a wrong depth and drags the estimate with it; but parked cars are a street's
  /// best near structure, so by default nothing is left out.
  std::string movable_classes;

  std::string validate() const;
};

/// Bits of the classes named in `names` (comma-separated) that `table_names` has.
std::uint32_t classMaskOf(const std::vector<std::string>& table_names, const std::string& names);

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
  /// @param[in] class_names the class table the edges' class masks refer to (resolves
  ///            options.movable_classes; empty: nothing is movable)
  explicit PointSampler(const PointSamplerOptions& options, const std::vector<std::string>& class_names = {})
      : options_(options), movable_mask_(classMaskOf(class_names, options.movable_classes)) {}

  /// @param[in] gray 8-bit image the edges come from
  /// @param[in] classes the frame's class evidence, or nullptr (canny edges): with it, edges with a
  ///            movable class and supportive pixels whose most probable class is movable are left out
  PointSample sample(const cv::Mat& gray, const EdgeSetView& edges, const ClassEvidence* classes = nullptr) const;

 private:
  /// @param excluded_classes edges with any of these classes are not sampled (0: none excluded)
  std::vector<std::uint32_t> sampleEdges(const EdgeSetView& edges, int width, int height, std::uint32_t excluded_classes) const;
  void sampleSupport(const cv::Mat& gray, const EdgeSetView& edges, int count, const ClassEvidence* classes,
                     PointSample* sample) const;

  PointSamplerOptions options_;
  std::uint32_t movable_mask_;  ///< options_.movable_classes in the class table
};

}  // namespace semantic_edge_vo
