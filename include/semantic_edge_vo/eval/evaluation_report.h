#pragma once
#include <cstddef>
#include <string>

#include "semantic_edge_vo/eval/trajectory_evaluator.h"

namespace semantic_edge_vo {

/// What was compared, for the report's header.
struct EvaluationSources {
  std::string gt_path, est_path;
  std::string gt_format, est_format;  ///< e.g. "kitti", "tum", "bag /odometry"
  std::size_t gt_poses = 0, est_poses = 0;
  std::string association;  ///< how the pairs were made, one sentence
};

/// The report as Markdown: sources, ATE (paper protocol, Sim(3), SE(3)), RPE, frame-to-frame
/// errors, KITTI drift (or why not), the paper-protocol segments, and what each figure means.
std::string evaluationMarkdown(const EvaluationSources& sources, const TrajectoryEvaluation& evaluation,
                               const TrajectoryEvaluationOptions& options);
/// The same figures as a JSON object (metres, degrees, percent; null for a non-finite number).
std::string evaluationJson(const EvaluationSources& sources, const TrajectoryEvaluation& evaluation,
                           const TrajectoryEvaluationOptions& options);

}  // namespace semantic_edge_vo
