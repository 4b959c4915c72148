#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Geometry>
#include <opencv2/core/mat.hpp>

#include "semantic_edge_vo/common/camera.h"
#include "semantic_edge_vo/common/edge_set.h"

namespace semantic_edge_vo {

/// Edge repeatability after Schenk and Fraundorfer, as in the paper's IV-B1: of the edge pixels of
/// frame i that should reappear in frame j, the fraction re-detected there.
struct RepeatabilityOptions {
  int sample_size = 9000;             ///< edge pixels drawn at random per detector and frame pair (paper: 9000)
  double radius = 1.5;                ///< a projected pixel is re-detected with an edge this close in frame j, px
  double min_depth = 0.5;             ///< nearer points (and depth 0: sky) are left out, m
  double occlusion_tolerance = 0.05;  ///< visible in j when j's depth there reaches (1 - this) x the projected depth
  int border = 2;                     ///< projections this close to the image border are left out (no edges there), px
  std::uint64_t seed = 1;             ///< of the random sample

  std::string validate() const;
};

/// One frame of a repeatability pair: a detector's edges plus the ground truth.
struct RepeatabilityFrame {
  EdgeSetView edges;
  cv::Mat depth;    ///< CV_32FC1, z along the optical axis, m; 0: unknown (sky)
  cv::Mat dynamic;  ///< CV_8UC1, nonzero on moving objects (left out); may be empty
  Eigen::Isometry3d T_world_cam = Eigen::Isometry3d::Identity();
};

/// Counts of one frame pair, or summed over pairs.
struct RepeatabilityCount {
  std::size_t edges = 0;       ///< edge pixels of frame i
  std::size_t eligible = 0;    ///< of them with depth, static, projecting inside frame j and visible there
  std::size_t sampled = 0;     ///< of those drawn at random (at most sample_size)
  std::size_t repeated = 0;    ///< sampled with an edge of frame j within the radius
  std::size_t same_class = 0;  ///< sampled with an edge of frame j within the radius sharing a class bit

  double rate() const { return sampled ? static_cast<double>(repeated) / static_cast<double>(sampled) : 0.0; }
  double classRate() const { return sampled ? static_cast<double>(same_class) / static_cast<double>(sampled) : 0.0; }
  RepeatabilityCount& operator+=(const RepeatabilityCount& other);
};

/// Projects a random sample of frame i's eligible edge pixels into frame j with ground-truth depth
/// and poses and counts those with an edge of frame j within the radius. A pixel's depth is the
/// nearest valid depth in its 3x3 neighbourhood (an edge on a silhouette belongs to the occluding
/// side); it is left out when any pixel of that neighbourhood is dynamic. It is visible in j when
/// the farthest depth in the 3x3 neighbourhood of its projection reaches (1 - tolerance) x its
/// projected depth. Both frames share `camera`. Deterministic for options.seed.
RepeatabilityCount measureRepeatability(const PinholeCamera& camera, const RepeatabilityFrame& first,
                                        const RepeatabilityFrame& second, const RepeatabilityOptions& options);

/// One row of the report: a detector's counts in one scene at one frame gap.
struct RepeatabilityResult {
  std::string scene, detector;
  int frame_gap = 1;
  bool semantic = false;  ///< class masks are meaningful (same-class figures reported)
  int pairs = 0;
  RepeatabilityCount count;
};

/// The rows as JSON: {"description", "radius_px", "sample_size", "results": [{scene, detector,
/// frame_gap, pairs, edges_per_frame, eligible, sampled, repeated, repeatability, same_class_repeatability
/// (null for non-semantic detectors)}]}.
std::string repeatabilityJson(const std::vector<RepeatabilityResult>& results, const RepeatabilityOptions& options,
                              const std::string& description);

}  // namespace semantic_edge_vo
