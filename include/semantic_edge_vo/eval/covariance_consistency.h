#pragma once
#include <cstddef>
#include <string>
#include <vector>

#include "semantic_edge_vo/common/tracked_motions.h"
#include "semantic_edge_vo/eval/trajectory_association.h"

namespace semantic_edge_vo {

/// NEES (normalised estimation error squared) of covariances against ground truth. For a consistent
/// covariance the NEES follows a chi-square distribution with the error's degrees of freedom.
struct NeesStatistics {
  std::size_t count = 0;
  int dof = 0;
  double mean = 0.0, median = 0.0;
  double above_95 = 0.0;  ///< fraction above the chi-square distribution's 95th percentile (consistent: 0.05)
  double expected_median = 0.0, bound_95 = 0.0;  ///< the chi-square distribution's (dof 3 or 6)
};

/// The tracker's covariance against the true motion from each frame's keyframe: xi =
/// log(T_cam_kf * T_cam_kf_true^-1), NEES xi^T Sigma^-1 xi over the whole pose, and over its rotation
/// and its translation alone (their marginal covariances).
struct CovarianceConsistency {
  NeesStatistics pose, rotation, translation;
  bool in_metres = false;  ///< only the motions tracked in metres were compared (there were some)
  /// Multiplies the estimate's translations (and their sigmas) before the comparison: 1 in metres,
  /// else the whole trajectory's Sim(3) scale (monocular units).
  double translation_scale = 1.0;
  std::size_t skipped = 0;  ///< motions whose frame or keyframe has no ground truth among the pairs
};

/// @param[in] sim3_scale the estimate's Sim(3) scale to ground truth (used when no motion is in metres)
/// Fails when no motion can be compared.
std::string covarianceConsistency(const PosePairs& pairs, const std::vector<TrackedMotion>& motions, double sim3_scale,
                                  CovarianceConsistency* result);

}  // namespace semantic_edge_vo
