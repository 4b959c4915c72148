#include "semantic_edge_vo/eval/trajectory_evaluator.h"

#include <sstream>

namespace semantic_edge_vo {
std::string TrajectoryEvaluationOptions::validate() const {
  std::string error = paper_ate.validate();
  if (!error.empty()) return "paper_ate: " + error;
  error = kitti_drift.validate();
  if (!error.empty()) return "kitti_drift: " + error;
  std::ostringstream out;
  if (rpe_delta_frames < 1) out << "rpe_delta_frames must be >= 1 (got " << rpe_delta_frames << ")";
  else if (!(min_gt_translation_m >= 0.0)) out << "min_gt_translation_m must be >= 0 (got " << min_gt_translation_m << ")";
  else if (!(min_keyframe_travel_m > 0.0)) out << "min_keyframe_travel_m must be > 0 (got " << min_keyframe_travel_m << ")";
  else if (end_frames < 2) out << "end_frames must be >= 2 (got " << end_frames << ")";
  else if (!(scale_stretch_m > 0.0)) out << "scale_stretch_m must be > 0 (got " << scale_stretch_m << ")";
  return out.str();
}

std::string evaluateTrajectory(const PosePairs& pairs, const TrajectoryEvaluationOptions& options,
                               const EstimateRecords& records, TrajectoryEvaluation* evaluation) {
  const std::vector<std::size_t>& keyframe_frames = records.keyframe_frames;
  const std::string options_error = options.validate();
  if (!options_error.empty()) return options_error;
  const std::vector<Eigen::Vector3d> gt = positionsOf(pairs.gt), est = positionsOf(pairs.est);
  TrajectoryEvaluation result;
  result.pairs = pairs.gt.size();
  result.gt_length_m = pathLength(gt);
  std::vector<std::size_t> frames;
  for (std::size_t i = 0; i < gt.size(); ++i) frames.push_back(pairs.groundTruthFrame(i));
  result.straight_line_m = straightLineErrors(gt, frames);
  std::string error = absoluteTrajectoryError(gt, est, true, &result.sim3_ate);
  if (error.empty()) error = absoluteTrajectoryError(gt, est, false, &result.se3_ate);
  if (error.empty()) error = frameToFrameErrors(pairs.gt, pairs.est, options.min_gt_translation_m, &result.frame_to_frame);
  if (!error.empty()) return error;

  constexpr std::size_t kScaleStep = 10;  // pairs: frame-to-frame jitter would lengthen the estimate's path
  result.path_scale = travelScale(gt, est, 0, kScaleStep);
  const auto end_frames = static_cast<std::size_t>(options.end_frames);
  result.end_scale = travelScale(gt, est, gt.size() > end_frames ? gt.size() - end_frames : 0, kScaleStep);
  result.scale_along_path = scaleAlongPath(gt, est, options.scale_stretch_m, kScaleStep);
  const double scale = result.sim3_ate.alignment.scale;
  result.paper_ate_unavailable = segmentedAte(gt, est, options.paper_ate, &result.paper_ate);
  if (result.paper_ate_unavailable.empty())
    result.paper_ate_unavailable = chainedSegmentAte(gt, est, result.paper_ate, &result.paper_chained_ate);
  result.rpe_unavailable = relativePoseError(pairs.gt, pairs.est, options.rpe_delta_frames, scale, &result.rpe);
  result.drift_unavailable = kittiDrift(pairs.gt, pairs.est, 1.0, options.kitti_drift, &result.drift_as_given);
  if (result.drift_unavailable.empty())
    result.drift_unavailable = kittiDrift(pairs.gt, pairs.est, scale, options.kitti_drift, &result.drift_sim3_scale);
  // The keyframes' pair indices: those of their ground-truth frames among the pairs.
  std::vector<std::size_t> keyframes;
  for (std::size_t i = 0, k = 0; i < pairs.gt.size() && k < keyframe_frames.size(); ++i) {
    while (k < keyframe_frames.size() && keyframe_frames[k] < pairs.groundTruthFrame(i)) ++k;
    if (k < keyframe_frames.size() && keyframe_frames[k] == pairs.groundTruthFrame(i)) keyframes.push_back(i);
  }
  result.keyframe_scale_unavailable = keyframe_frames.empty() ? "no keyframes given"
                                                              : keyframeScaleChanges(gt, est, keyframes, options.min_keyframe_travel_m,
                                                                                     &result.keyframe_scale);
  result.covariance_unavailable = records.tracked_motions.empty()
                                      ? "no tracked motions (none given, or none trusted)"
                                      : covarianceConsistency(pairs, records.tracked_motions, scale, &result.covariance);
  *evaluation = std::move(result);
  return "";
}

}  // namespace semantic_edge_vo
