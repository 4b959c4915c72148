#pragma once
#include <cstddef>
#include <string>

#include "semantic_edge_vo/eval/covariance_consistency.h"
#include "semantic_edge_vo/eval/trajectory_association.h"
#include "semantic_edge_vo/eval/trajectory_evaluation.h"

namespace semantic_edge_vo {

struct TrajectoryEvaluationOptions {
  AteProtocolOptions paper_ate;
  int rpe_delta_frames = 1;
  KittiDriftOptions kitti_drift;
  double min_gt_translation_m = 0.05;  ///< frame-to-frame directions need this much true motion, metres
  double min_keyframe_travel_m = 0.2;  ///< keyframe intervals need this much true travel for their scale, metres
  int end_frames = 100;                ///< the scale at the end is measured over this many last pairs (all when fewer)
  double scale_stretch_m = 20.0;       ///< the scale along the path is measured over stretches of this much true travel, metres

  std::string validate() const;
};

/// All metrics of one estimate against its ground truth. A metric that could not be computed keeps
/// its defaults and says why in the matching `*_unavailable` (empty when it was computed).
struct TrajectoryEvaluation {
  std::size_t pairs = 0;     ///< corresponding poses evaluated
  double gt_length_m = 0.0;  ///< ground-truth path length over them
  AteResult sim3_ate;        ///< whole trajectory, Umeyama Sim(3)
  AteResult se3_ate;         ///< whole trajectory, Umeyama SE(3)
  ErrorStatistics straight_line_m;  ///< the ground truth against its closest constant-speed straight line (reference)
  SegmentedAteResult paper_ate;       ///< the paper's protocol, each segment Sim(3)-aligned on its own
  AteResult paper_chained_ate;        ///< the paper's protocol as stated: segments' scales, chained, one SE(3) alignment
  std::string paper_ate_unavailable;  ///< of both
  RpeResult rpe;  ///< estimated translations scaled by the Sim(3) scale
  std::string rpe_unavailable;
  KittiDriftResult drift_as_given;    ///< estimate as it is (the devkit, for metric estimates)
  KittiDriftResult drift_sim3_scale;  ///< estimated translations scaled by the Sim(3) scale (monocular)
  std::string drift_unavailable;
  FrameToFrameErrors frame_to_frame;
  /// The estimate's scale as it is (1: metres; travelScale over steps of 10 pairs): over the whole
  /// path and over the last end_frames pairs.
  double path_scale = 0.0, end_scale = 0.0;
  ScaleAlongPath scale_along_path;  ///< stretches of scale_stretch_m (travelScale over steps of 10 pairs)
  KeyframeScaleChanges keyframe_scale;  ///< with the estimate's keyframes
  std::string keyframe_scale_unavailable;
  CovarianceConsistency covariance;  ///< with the estimate's tracked motions
  std::string covariance_unavailable;
};

/// What a run recorded beside its poses; each part may be empty (its metrics are then not available).
struct EstimateRecords {
  std::vector<std::size_t> keyframe_frames;    ///< ground-truth frame numbers of the estimate's keyframes
  std::vector<TrackedMotion> tracked_motions;  ///< each frame's motion from its keyframe, with its covariance
};

/// Computes every metric on the pairs; fails only when the whole-trajectory alignment is impossible
/// (fewer than 3 pairs, or an estimate that does not move).
std::string evaluateTrajectory(const PosePairs& pairs, const TrajectoryEvaluationOptions& options, const EstimateRecords& records,
                               TrajectoryEvaluation* evaluation);

}  // namespace semantic_edge_vo
