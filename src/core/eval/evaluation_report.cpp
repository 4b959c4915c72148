#include "semantic_edge_vo/eval/evaluation_report.h"

#include "semantic_edge_vo/support/json_text.h"

#include <cmath>
#include <cstdio>
#include <sstream>
#include <utility>
#include <vector>

namespace semantic_edge_vo {
namespace {

using Fields = std::vector<std::pair<std::string, std::string>>;  ///< key, rendered JSON value

// --- JSON --------------------------------------------------------------------------------------

std::string jsonNumber(double value) {
  if (!std::isfinite(value)) return "null";
  char text[32];
  std::snprintf(text, sizeof(text), "%.10g", value);
  return text;
}

std::string jsonCount(std::size_t value) { return std::to_string(value); }

/// An object: one field a line at `depth` >= 0 (two spaces a level), on one line when depth < 0.
std::string jsonObject(const Fields& fields, int depth) {
  const std::string inner = depth < 0 ? " " : "\n" + std::string(2 * static_cast<std::size_t>(depth + 1), ' ');
  const std::string outer = depth < 0 ? " " : "\n" + std::string(2 * static_cast<std::size_t>(depth), ' ');
  std::string text = "{";
  for (std::size_t i = 0; i < fields.size(); ++i)
    text += (i ? "," : "") + inner + jsonString(fields[i].first) + ": " + fields[i].second;
  return text + outer + "}";
}

std::string jsonArray(const std::vector<std::string>& items, int depth) {
  const std::string inner = "\n" + std::string(2 * static_cast<std::size_t>(depth + 1), ' ');
  std::string text = "[";
  for (std::size_t i = 0; i < items.size(); ++i) text += (i ? "," : "") + inner + items[i];
  return text + (items.empty() ? "" : "\n" + std::string(2 * static_cast<std::size_t>(depth), ' ')) + "]";
}

std::string jsonStatistics(const ErrorStatistics& s) {
  return jsonObject({{"count", jsonCount(s.count)},
                     {"rmse", jsonNumber(s.rmse)},
                     {"mean", jsonNumber(s.mean)},
                     {"median", jsonNumber(s.median)},
                     {"max", jsonNumber(s.max)}},
                    -1);
}

std::string jsonNeesStatistics(const NeesStatistics& s) {
  return jsonObject({{"count", jsonCount(s.count)},
                     {"dof", std::to_string(s.dof)},
                     {"median", jsonNumber(s.median)},
                     {"mean", jsonNumber(s.mean)},
                     {"above_95", jsonNumber(s.above_95)}},
                    -1);
}

std::string jsonAvailability(const std::string& unavailable) {
  return unavailable.empty() ? "null" : jsonString(unavailable);
}

std::string jsonAte(const AteResult& ate, int depth) {
  const SimilarityTransform& a = ate.alignment;
  std::string rotation = "[";
  for (int r = 0; r < 3; ++r)
    rotation += std::string(r ? ", " : "") + "[" + jsonNumber(a.rotation(r, 0)) + ", " + jsonNumber(a.rotation(r, 1)) +
                ", " + jsonNumber(a.rotation(r, 2)) + "]";
  const std::string translation = "[" + jsonNumber(a.translation.x()) + ", " + jsonNumber(a.translation.y()) + ", " +
                                  jsonNumber(a.translation.z()) + "]";
  return jsonObject({{"statistics", jsonStatistics(ate.error_m)},
                     {"scale", jsonNumber(a.scale)},
                     {"rotation", rotation + "]"},
                     {"translation_m", translation}},
                    depth);
}

std::string jsonPaperAte(const TrajectoryEvaluation& e, const AteProtocolOptions& options, int depth) {
  std::vector<std::string> segments;
  for (const AteSegment& s : e.paper_ate.segments)
    segments.push_back(jsonObject({{"first", jsonCount(s.first)},
                                   {"count", jsonCount(s.count)},
                                   {"scale", jsonNumber(s.scale)},
                                   {"rmse_m", jsonNumber(s.rmse_m)}},
                                  -1));
  return jsonObject({{"unavailable", jsonAvailability(e.paper_ate_unavailable)},
                     {"discard_first_poses", std::to_string(options.discard_first_poses)},
                     {"segment_frames", std::to_string(options.segment_frames)},
                     {"statistics", jsonStatistics(e.paper_ate.error_m)},
                     {"segments", jsonArray(segments, depth + 1)}},
                    depth);
}

std::string jsonNees(const TrajectoryEvaluation& e, int depth) {
  const CovarianceConsistency& c = e.covariance;
  return jsonObject({{"unavailable", jsonAvailability(e.covariance_unavailable)},
                     {"in_metres", c.in_metres ? "true" : "false"},
                     {"translation_scale", jsonNumber(c.translation_scale)},
                     {"skipped", jsonCount(c.skipped)},
                     {"pose", jsonNeesStatistics(c.pose)},
                     {"rotation", jsonNeesStatistics(c.rotation)},
                     {"translation", jsonNeesStatistics(c.translation)}},
                    depth);
}

std::string jsonDrift(const TrajectoryEvaluation& e, const KittiDriftOptions& options, int depth) {
  std::vector<std::string> lengths;
  for (std::size_t i = 0; i < e.drift_as_given.lengths.size(); ++i) {
    const KittiDriftLength& given = e.drift_as_given.lengths[i];
    lengths.push_back(jsonObject({{"length_m", jsonNumber(given.length_m)},
                                  {"segments", jsonCount(given.count)},
                                  {"translation_percent", jsonNumber(given.translation_percent)},
                                  {"translation_percent_sim3_scale",
                                   jsonNumber(e.drift_sim3_scale.lengths[i].translation_percent)},
                                  {"rotation_deg_per_100m", jsonNumber(given.rotation_deg_per_100m)}},
                                 -1));
  }
  return jsonObject({{"unavailable", jsonAvailability(e.drift_unavailable)},
                     {"step_frames", std::to_string(options.step_frames)},
                     {"segments", jsonCount(e.drift_as_given.count)},
                     {"translation_percent", jsonNumber(e.drift_as_given.translation_percent)},
                     {"translation_percent_sim3_scale", jsonNumber(e.drift_sim3_scale.translation_percent)},
                     {"rotation_deg_per_100m", jsonNumber(e.drift_as_given.rotation_deg_per_100m)},
                     {"lengths", jsonArray(lengths, depth + 1)}},
                    depth);
}

std::string jsonScaleAlongPath(const TrajectoryEvaluation& e, const TrajectoryEvaluationOptions& options, int depth) {
  const ScaleAlongPath& along = e.scale_along_path;
  const double path = e.path_scale > 0.0 ? e.path_scale : std::nan("");
  std::vector<std::string> stretches;
  for (const ScaleStretch& s : along.stretches)
    stretches.push_back(jsonObject({{"first_pair", jsonCount(s.first)},
                                    {"last_pair", jsonCount(s.last)},
                                    {"from_m", jsonNumber(s.from_m)},
                                    {"to_m", jsonNumber(s.to_m)},
                                    {"scale", jsonNumber(s.scale)},
                                    {"relative", jsonNumber(s.scale / path)}},
                                   -1));
  const bool any = !along.stretches.empty();
  return jsonObject({{"stretch_m", jsonNumber(options.scale_stretch_m)},
                     {"lowest_relative", any ? jsonNumber(along.stretches[along.lowest].scale / path) : "null"},
                     {"highest_relative", any ? jsonNumber(along.stretches[along.highest].scale / path) : "null"},
                     {"largest_change_between_neighbours", jsonNumber(along.largest_change)},
                     {"stretches", jsonArray(stretches, depth + 1)}},
                    depth);
}

// --- Markdown ----------------------------------------------------------------------------------

std::string figure(double value) {
  if (!std::isfinite(value)) return "n/a";
  char text[32];
  std::snprintf(text, sizeof(text), "%.4g", value);
  return text;
}

/// Text for a table cell: pipes escaped.
std::string cell(const std::string& text) {
  std::string escaped;
  for (char c : text) escaped += c == '|' ? std::string("\\|") : std::string(1, c);
  return escaped;
}

std::string statisticsRow(const std::string& name, const ErrorStatistics& s) {
  return "| " + name + " | " + figure(s.rmse) + " | " + figure(s.mean) + " | " + figure(s.median) + " | " +
         figure(s.max) + " | " + std::to_string(s.count) + " |\n";
}

constexpr const char* kStraightLine = "reference: constant-speed straight line closest to the ground truth";

void markdownAte(const TrajectoryEvaluation& e, const AteProtocolOptions& options, std::ostringstream& md) {
  md << "## Absolute trajectory error (camera positions, m)\n\n"
     << "| alignment | RMSE | mean | median | max | poses |\n|---|---:|---:|---:|---:|---:|\n";
  const std::string frames = std::to_string(options.segment_frames);
  const std::string discarded = "first " + std::to_string(options.discard_first_poses) + " poses discarded";
  const std::string paper = "paper: " + discarded + ", Sim(3) per " + frames + " frames",
                    chained = "paper as stated: " + discarded + ", motion scaled per " + frames +
                              " frames from ground truth, chained, one SE(3) alignment";
  if (e.paper_ate_unavailable.empty())
    md << statisticsRow(paper, e.paper_ate.error_m) << statisticsRow(chained, e.paper_chained_ate.error_m);
  else md << "| " << paper << " | not available: " << cell(e.paper_ate_unavailable) << " | | | | |\n";
  const double se3_percent = e.gt_length_m > 0.0 ? 100.0 * e.se3_ate.error_m.rmse / e.gt_length_m : 0.0;
  md << statisticsRow("Sim(3) Umeyama, whole trajectory (scale " + figure(e.sim3_ate.alignment.scale) + ")",
                      e.sim3_ate.error_m)
     << statisticsRow("SE(3) Umeyama, whole trajectory: no scale from ground truth (RMSE " + figure(se3_percent) + " % of the path)",
                      e.se3_ate.error_m)
     << (e.straight_line_m.count ? statisticsRow(kStraightLine, e.straight_line_m)
                                 : "| " + std::string(kStraightLine) + " | not available: one frame number | | | | |\n")
     << "\n";
}

void markdownRelative(const TrajectoryEvaluation& e, const TrajectoryEvaluationOptions& options,
                      std::ostringstream& md) {
  md << "## Relative pose error over " << options.rpe_delta_frames << " frame(s)\n\n";
  if (!e.rpe_unavailable.empty()) {
    md << "Not available: " << e.rpe_unavailable << "\n\n";
  } else {
    md << "Estimated translations multiplied by the whole-trajectory Sim(3) scale.\n\n"
       << "| error | RMSE | mean | median | max | motions |\n|---|---:|---:|---:|---:|---:|\n"
       << statisticsRow("translation (m)", e.rpe.translation_m) << statisticsRow("rotation (deg)", e.rpe.rotation_deg)
       << "\n";
  }
  const FrameToFrameErrors& f = e.frame_to_frame;
  md << "## Frame-to-frame motion errors (scale-free)\n\n| error | mean (deg) | motions |\n|---|---:|---:|\n"
     << "| rotation of each motion | " << figure(f.mean_rotation_error_deg) << " | " << f.motions << " |\n"
     << "| translation direction (true motion >= " << figure(options.min_gt_translation_m) << " m) | "
     << (f.direction_motions ? figure(f.mean_direction_error_deg) : "n/a") << " | " << f.direction_motions << " |\n\n";
}

void markdownDrift(const TrajectoryEvaluation& e, const KittiDriftOptions& options, std::ostringstream& md) {
  md << "## KITTI devkit drift\n\n";
  if (!e.drift_unavailable.empty()) {
    md << "Not available: " << e.drift_unavailable << ".\n\n";
    return;
  }
  md << "Segments start every " << options.step_frames << " frames. \"As given\" is the devkit on the estimate as it "
     << "is (metric estimates); \"Sim(3) scale\" first multiplies the estimated translations by the whole-trajectory "
     << "Sim(3) scale (monocular estimates). Rotation drift does not depend on scale.\n\n"
     << "| segment length (m) | segments | translation, as given (%) | translation, Sim(3) scale (%) | "
     << "rotation (deg/100 m) |\n|---:|---:|---:|---:|---:|\n";
  for (std::size_t i = 0; i < e.drift_as_given.lengths.size(); ++i) {
    const KittiDriftLength& given = e.drift_as_given.lengths[i];
    md << "| " << figure(given.length_m) << " | " << given.count << " | " << figure(given.translation_percent)
       << " | " << figure(e.drift_sim3_scale.lengths[i].translation_percent) << " | "
       << figure(given.rotation_deg_per_100m) << " |\n";
  }
  md << "| **all** | " << e.drift_as_given.count << " | **" << figure(e.drift_as_given.translation_percent)
     << "** | **" << figure(e.drift_sim3_scale.translation_percent) << "** | **"
     << figure(e.drift_as_given.rotation_deg_per_100m) << "** |\n\n";
}

void markdownScale(const TrajectoryEvaluation& e, const TrajectoryEvaluationOptions& options, std::ostringstream& md) {
  md << "## Scale as it is\n\nThe estimate's travel over the true travel, measured over steps of 10 poses, with no alignment "
        "(1: metres, the figure of an estimate run with a camera height).\n\n| over | scale | error (%) |\n|---|---:|---:|\n"
     << "| the whole path | " << figure(e.path_scale) << " | " << figure(100.0 * (e.path_scale - 1.0)) << " |\n"
     << "| the last " << options.end_frames << " poses | " << figure(e.end_scale) << " | " << figure(100.0 * (e.end_scale - 1.0))
     << " |\n\n";
}

void markdownScaleAlongPath(const TrajectoryEvaluation& e, const TrajectoryEvaluationOptions& options, std::ostringstream& md) {
  const ScaleAlongPath& along = e.scale_along_path;
  md << "## Scale along the path\n\n";
  if (along.stretches.empty() || !(e.path_scale > 0.0)) {
    md << "Not available: the ground truth does not move " << figure(options.scale_stretch_m) << " m.\n\n";
    return;
  }
  const auto cells = [&](const ScaleStretch& s) {
    return figure(s.scale / e.path_scale) + " | " + figure(s.from_m) + "-" + figure(s.to_m) + " m";
  };
  md << "The estimate's travel over the true travel in each stretch of " << figure(options.scale_stretch_m)
     << " m of true travel, over the same for the whole path (1: the estimate's average scale); drawn in "
        "scale_along_path.png. A monocular scale that drifts (in turns, after a restart) shows here.\n\n"
     << "| stretches | lowest | at | highest | at | largest change between neighbours (%) |\n|---:|---:|---|---:|---|---:|\n| "
     << along.stretches.size() << " | " << cells(along.stretches[along.lowest]) << " | " << cells(along.stretches[along.highest])
     << " | " << figure(100.0 * along.largest_change) << " |\n\n";
}

void markdownKeyframeScale(const TrajectoryEvaluation& e, const TrajectoryEvaluationOptions& options, std::ostringstream& md) {
  md << "## Scale between consecutive keyframes\n\n";
  if (!e.keyframe_scale_unavailable.empty()) {
    md << "Not available: " << e.keyframe_scale_unavailable << ".\n\n";
    return;
  }
  md << "The estimated travel over the true one between consecutive keyframes (intervals of at least "
     << figure(options.min_keyframe_travel_m) << " m of true travel): its largest change from one interval to the next.\n\n"
     << "| intervals | largest change (%) | at pair |\n|---:|---:|---:|\n| " << e.keyframe_scale.intervals << " | "
     << figure(100.0 * e.keyframe_scale.largest_change) << " | " << e.keyframe_scale.at_pair << " |\n\n";
}

void markdownCovariance(const TrajectoryEvaluation& e, std::ostringstream& md) {
  md << "## Tracking covariance against ground truth (NEES)\n\n";
  if (!e.covariance_unavailable.empty()) {
    md << "Not available: " << e.covariance_unavailable << ".\n\n";
    return;
  }
  const CovarianceConsistency& c = e.covariance;
  md << "Each frame's motion from its keyframe as tracked, against the true one: NEES = xi^T Sigma^-1 xi with xi = "
        "log(T_cam_kf T_cam_kf_true^-1) and Sigma the tracker's covariance (the one published). A consistent covariance "
        "gives the chi-square median and 5 % above its 95th percentile; larger: the covariance is too small (overconfident). "
     << (c.in_metres ? "Motions tracked in metres only."
                                    : "Estimated translations multiplied by the Sim(3) scale " + figure(c.translation_scale) + ".")
     << (c.skipped ? " " + std::to_string(c.skipped) + " motions without ground truth skipped." : "") << "\n\n"
     << "| error | dof | motions | median (consistent) | mean (consistent) | above the 95th percentile (consistent: 5 %) |\n"
        "|---|---:|---:|---:|---:|---:|\n";
  const auto row = [&](const char* name, const NeesStatistics& s) {
    md << "| " << name << " | " << s.dof << " | " << s.count << " | " << figure(s.median) << " (" << figure(s.expected_median) << ") | "
       << figure(s.mean) << " (" << s.dof << ") | " << figure(100.0 * s.above_95) << " % |\n";
  };
  row("pose", c.pose);
  row("rotation", c.rotation);
  row("translation", c.translation);
  md << "\n";
}

void markdownSegments(const TrajectoryEvaluation& e, std::ostringstream& md) {
  if (!e.paper_ate_unavailable.empty()) return;
  md << "## Paper-protocol segments\n\n| first pair | poses | Sim(3) scale | RMSE (m) |\n|---:|---:|---:|---:|\n";
  for (const AteSegment& s : e.paper_ate.segments)
    md << "| " << s.first << " | " << s.count << " | " << figure(s.scale) << " | " << figure(s.rmse_m) << " |\n";
  md << "\n";
}

}  // namespace


std::string evaluationMarkdown(const EvaluationSources& sources, const TrajectoryEvaluation& evaluation,
                               const TrajectoryEvaluationOptions& options) {
  std::ostringstream md;
  md << "# Trajectory evaluation\n\n| | |\n|---|---|\n"
     << "| ground truth | `" << cell(sources.gt_path) << "` (" << sources.gt_format << ", " << sources.gt_poses
     << " poses) |\n"
     << "| estimate | `" << cell(sources.est_path) << "` (" << sources.est_format << ", " << sources.est_poses
     << " poses) |\n"
     << "| association | " << cell(sources.association) << " |\n"
     << "| pose pairs | " << evaluation.pairs << ", ground-truth path " << figure(evaluation.gt_length_m) << " m |\n\n";
  markdownAte(evaluation, options.paper_ate, md);
  markdownRelative(evaluation, options, md);
  markdownDrift(evaluation, options.kitti_drift, md);
  markdownScale(evaluation, options, md);
  markdownScaleAlongPath(evaluation, options, md);
  markdownKeyframeScale(evaluation, options, md);
  markdownCovariance(evaluation, md);
  markdownSegments(evaluation, md);
  md << "## Method\n\n"
     << "- ATE: RMSE of the differences of camera positions after aligning the estimate to the ground truth with "
        "Umeyama's least-squares method (Sim(3): rotation, translation and scale; SE(3): no scale).\n"
     << "- Paper protocol (\"no loop closure, scale recovered from ground truth every 200 frames, first ten poses "
        "discarded\"): after dropping the first poses, the estimate is cut into consecutive segments of "
     << options.paper_ate.segment_frames
     << " frames (a remainder shorter than half a segment joins the last one) and each segment gets its own Sim(3) "
        "alignment to the ground truth; the RMSE is over all poses of all segments. Re-aligning pose and scale per "
        "segment is what re-setting the scale from ground truth means for a trajectory evaluated afterwards: the "
        "error then measures drift within 200 frames, not the accumulated drift of the whole sequence.\n"
     << "- Paper protocol as stated: the same segments' Sim(3) scales multiply the estimated motion within each "
        "segment, the motions are chained from the first kept pose, and the chained trajectory gets one SE(3) "
        "alignment: the scale comes from ground truth, the drift of position and heading accumulates.\n"
     << "- SE(3) ATE and the KITTI drift \"as given\" take no scale from ground truth: the figures of a metric "
        "estimate (run with a camera height).\n"
     << "- RPE: E = (gt_i^-1 gt_j)^-1 (est_i^-1 est_j), j = i + delta; translation |t(E)|, rotation angle(R(E)).\n"
     << "- Frame-to-frame errors: angle between the true and estimated rotation of each motion i -> i+1, and angle "
        "between their translation directions; both independent of the estimate's scale.\n"
     << "- KITTI drift: the devkit's evaluate_odometry (segments of 100..800 m of ground-truth path length, error of "
        "the segment's motion divided by its length, averaged over all segments).\n";
  return md.str();
}

std::string evaluationJson(const EvaluationSources& sources, const TrajectoryEvaluation& evaluation,
                           const TrajectoryEvaluationOptions& options) {
  const FrameToFrameErrors& f = evaluation.frame_to_frame;
  const Fields fields = {
      {"ground_truth", jsonObject({{"path", jsonString(sources.gt_path)},
                                   {"format", jsonString(sources.gt_format)},
                                   {"poses", jsonCount(sources.gt_poses)}},
                                  -1)},
      {"estimate", jsonObject({{"path", jsonString(sources.est_path)},
                               {"format", jsonString(sources.est_format)},
                               {"poses", jsonCount(sources.est_poses)}},
                              -1)},
      {"association", jsonString(sources.association)},
      {"pairs", jsonCount(evaluation.pairs)},
      {"gt_length_m", jsonNumber(evaluation.gt_length_m)},
      {"scale", jsonObject({{"path", jsonNumber(evaluation.path_scale)},
                            {"end", jsonNumber(evaluation.end_scale)},
                            {"end_frames", std::to_string(options.end_frames)}},
                           -1)},
      {"scale_along_path", jsonScaleAlongPath(evaluation, options, 1)},
      {"ate_m", jsonObject({{"paper", jsonPaperAte(evaluation, options.paper_ate, 2)},
                            {"paper_chained", jsonAte(evaluation.paper_chained_ate, 2)},
                            {"sim3", jsonAte(evaluation.sim3_ate, 2)},
                            {"se3", jsonAte(evaluation.se3_ate, 2)},
                            {"straight_line_reference", jsonObject({{"statistics", jsonStatistics(evaluation.straight_line_m)}}, 2)}},
                           1)},
      {"rpe", jsonObject({{"unavailable", jsonAvailability(evaluation.rpe_unavailable)},
                          {"delta_frames", std::to_string(options.rpe_delta_frames)},
                          {"translation_m", jsonStatistics(evaluation.rpe.translation_m)},
                          {"rotation_deg", jsonStatistics(evaluation.rpe.rotation_deg)}},
                         1)},
      {"frame_to_frame", jsonObject({{"motions", jsonCount(f.motions)},
                                     {"direction_motions", jsonCount(f.direction_motions)},
                                     {"min_gt_translation_m", jsonNumber(options.min_gt_translation_m)},
                                     {"mean_rotation_error_deg", jsonNumber(f.mean_rotation_error_deg)},
                                     {"mean_direction_error_deg",
                                      f.direction_motions ? jsonNumber(f.mean_direction_error_deg) : "null"}},
                                    1)},
      {"kitti_drift", jsonDrift(evaluation, options.kitti_drift, 1)},
      {"keyframe_scale", jsonObject({{"unavailable", jsonAvailability(evaluation.keyframe_scale_unavailable)},
                                     {"intervals", jsonCount(evaluation.keyframe_scale.intervals)},
                                     {"largest_change", jsonNumber(evaluation.keyframe_scale.largest_change)},
                                     {"at_pair", jsonCount(evaluation.keyframe_scale.at_pair)}},
                                    1)},
      {"tracking_nees", jsonNees(evaluation, 1)},
  };
  return jsonObject(fields, 0) + "\n";
}

}  // namespace semantic_edge_vo
