// Evaluates an estimated camera trajectory against ground truth: ATE (the paper's protocol, Sim(3),
// SE(3)), RPE, scale-free frame-to-frame errors and the KITTI devkit drift. Prints the Markdown
// report and writes DIR/evaluation.md, DIR/evaluation.json, DIR/trajectory_top_down.png and
// DIR/scale_along_path.png.
//   evaluate_trajectory GT EST [options]      (run with --help for the options)
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include <opencv2/imgcodecs.hpp>

#include "semantic_edge_vo/support/command_line.h"
#include "semantic_edge_vo/eval/evaluation_report.h"
#include "semantic_edge_vo/ros/bags/bag_trajectory.h"
#include "semantic_edge_vo/ros/camera_extrinsic.h"
#include "semantic_edge_vo/eval/trajectory_evaluator.h"
#include "semantic_edge_vo/eval/line_plot.h"
#include "semantic_edge_vo/eval/trajectory_plot.h"

namespace sevo = semantic_edge_vo;
namespace fs = std::filesystem;

namespace {

const char* const kUsage = R"(usage: evaluate_trajectory GT EST [options]
  GT, EST            trajectory files: KITTI poses (12 numbers a line, camera-to-world) or TUM
                     (timestamp tx ty tz qx qy qz qw); EST may also be a .bag with nav_msgs/Odometry
  --format F         kitti | tum | auto (default: auto, from the number of columns of each file)
  --output DIR       where evaluation.md, evaluation.json, trajectory_top_down.png, scale_along_path.png go (default: .)
  --bag-topic T      odometry topic in a bag EST (default: /odometry)
  --bag-extrinsic E  optical | identity: T_base_cam the odometry ran with; optical (default) is the
                     tracking nodelet's default camera mount, identity when the bag holds camera poses
  --gt-times FILE    KITTI times.txt giving GT poses stamps, to associate a stamped EST by time
  --associate A      auto | index | stamps (default auto: stamps when both have them, else index)
  --max-time-diff S  largest stamp difference of an associated pair, seconds (default 0.01)
  --est-time-offset S  added to EST stamps before association, seconds (default 0)
  --discard N        paper ATE: poses discarded at the start (default 10)
  --segment-frames N paper ATE: frames per Sim(3)-aligned segment (default 200)
  --rpe-delta N      RPE frame delta (default 1)
  --end-frames N     the scale at the end is measured over the last N poses (default 100)
  --scale-stretch M  the scale along the path is measured per M metres of true travel (default 20)
  --first-frame N    evaluate the pairs from ground-truth frame N on (default 0: all); e.g. 12 for
                     KITTI 06, whose first 12 ground-truth poses are extrapolated, not measured
  --keyframes FILE   the estimate's keyframes: run_sequence's timing.txt, or one frame number a line;
                     adds the largest change of scale between consecutive keyframes
  --tracked-motions FILE  run_sequence's tracked_motions.txt: each frame's motion from its keyframe
                     with the tracker's covariance; adds the covariance's NEES against ground truth
)";

struct Arguments {
  std::string gt_path, est_path, format = "auto", output = ".", bag_topic = "/odometry", bag_extrinsic = "optical";
  std::string gt_times, associate = "auto", keyframes, tracked_motions;
  double max_time_diff = 0.01, est_time_offset = 0.0;
  int first_frame = 0;
  sevo::TrajectoryEvaluationOptions options;
};

/// Empty on success, otherwise what is wrong with the command line.
std::string parseArguments(int argc, char** argv, Arguments* args) {
  std::vector<std::string> positional;
  for (int i = 1; i < argc; ++i) {
    const std::string flag = argv[i];
    if (flag.rfind("--", 0) != 0) {
      positional.push_back(flag);
      continue;
    }
    if (i + 1 >= argc || argv[i + 1][0] == '\0') return flag + " needs a value";  // parseNumber would keep the default
    const std::string value = argv[++i];
    const auto oneOf = [&](std::initializer_list<const char*> choices) {
      for (const char* choice : choices)
        if (value == choice) return std::string();
      return "bad value '" + value + "' for " + flag;
    };
    std::string error;
    if (flag == "--format") args->format = value, error = oneOf({"auto", "kitti", "tum"});
    else if (flag == "--output") args->output = value;
    else if (flag == "--bag-topic") args->bag_topic = value;
    else if (flag == "--bag-extrinsic") args->bag_extrinsic = value, error = oneOf({"optical", "identity"});
    else if (flag == "--gt-times") args->gt_times = value;
    else if (flag == "--keyframes") args->keyframes = value;
    else if (flag == "--tracked-motions") args->tracked_motions = value;
    else if (flag == "--associate") args->associate = value, error = oneOf({"auto", "index", "stamps"});
    else if (flag == "--max-time-diff") error = sevo::parseNumber(flag, value, &args->max_time_diff);
    else if (flag == "--est-time-offset") error = sevo::parseNumber(flag, value, &args->est_time_offset);
    else if (flag == "--discard") error = sevo::parseNumber(flag, value, &args->options.paper_ate.discard_first_poses);
    else if (flag == "--segment-frames") error = sevo::parseNumber(flag, value, &args->options.paper_ate.segment_frames);
    else if (flag == "--rpe-delta") error = sevo::parseNumber(flag, value, &args->options.rpe_delta_frames);
    else if (flag == "--end-frames") error = sevo::parseNumber(flag, value, &args->options.end_frames);
    else if (flag == "--scale-stretch") error = sevo::parseNumber(flag, value, &args->options.scale_stretch_m);
    else if (flag == "--first-frame") {
      error = sevo::parseNumber(flag, value, &args->first_frame);
      if (error.empty() && args->first_frame < 0) error = "--first-frame takes a frame index >= 0 (got '" + value + "')";
    } else return "unknown option " + flag;
    if (!error.empty()) return error;
  }
  if (positional.size() != 2) return "expected GT and EST, got " + std::to_string(positional.size()) + " file name(s)";
  args->gt_path = positional[0];
  args->est_path = positional[1];
  return args->options.validate();
}

/// Reads a text trajectory in the requested (or detected) format; `format_name` says which.
std::string readTextTrajectory(const std::string& path, const std::string& requested, sevo::Trajectory* trajectory,
                               std::string* format_name) {
  sevo::TrajectoryFormat format = sevo::TrajectoryFormat::kKitti;
  if (requested == "auto") {
    const std::string error = sevo::detectTrajectoryFormat(path, &format);
    if (!error.empty()) return error;
  } else {
    sevo::parseTrajectoryFormat(requested, &format);  // checked by parseArguments
  }
  *format_name = sevo::toString(format);
  return sevo::readTrajectory(path, format, trajectory);
}

std::string readInputs(const Arguments& args, sevo::Trajectory* gt, sevo::Trajectory* est,
                       sevo::EvaluationSources* sources) {
  std::string error = readTextTrajectory(args.gt_path, args.format, gt, &sources->gt_format);
  if (!error.empty()) return error;
  if (!args.gt_times.empty()) {
    error = sevo::readTimes(args.gt_times, &gt->stamps);
    if (!error.empty()) return error;
    if (gt->stamps.size() != gt->size())
      return args.gt_times + ": " + std::to_string(gt->stamps.size()) + " stamps for " + std::to_string(gt->size()) +
             " poses in " + args.gt_path;
    sources->gt_format += " + times " + args.gt_times;
  }
  if (fs::path(args.est_path).extension() == ".bag") {
    const Eigen::Isometry3d T_base_cam = args.bag_extrinsic == "optical" ? sevo::opticalDefault()
                                                                         : Eigen::Isometry3d::Identity();
    error = sevo::readOdometryBag(args.est_path, args.bag_topic, T_base_cam, est);
    sources->est_format = "bag " + args.bag_topic + " (" + args.bag_extrinsic + " extrinsic)";
  } else {
    error = readTextTrajectory(args.est_path, args.format, est, &sources->est_format);
  }
  for (double& stamp : est->stamps) stamp += args.est_time_offset;
  sources->gt_path = args.gt_path;
  sources->est_path = args.est_path;
  sources->gt_poses = gt->size();
  sources->est_poses = est->size();
  return error;
}

std::string associate(const Arguments& args, const sevo::Trajectory& gt, const sevo::Trajectory& est,
                      sevo::PosePairs* pairs, std::string* description) {
  const bool stamped = gt.hasStamps() && est.hasStamps();
  if (args.associate == "stamps" || (args.associate == "auto" && stamped)) {
    if (!stamped)
      return "--associate stamps needs stamps in both trajectories (a KITTI GT gets them from --gt-times)";
    const std::string error = sevo::associateByStamps(gt, est, args.max_time_diff, pairs);
    if (!error.empty()) return error + "; check --est-time-offset, or use --associate index";
    std::ostringstream text;
    text << "by time stamp, nearest within " << args.max_time_diff << " s";
    if (args.est_time_offset != 0.0) text << ", estimate stamps shifted by " << args.est_time_offset << " s";
    *description = text.str();
    return "";
  }
  *pairs = sevo::associateByIndex(gt, est);
  *description = "by index (pose i with pose i), over the first " + std::to_string(pairs->gt.size()) + " poses";
  return "";
}

/// Keeps the pairs from --first-frame on and says so in the description.
std::string keepFromFirstFrame(const Arguments& args, sevo::PosePairs* pairs, std::string* description) {
  if (args.first_frame == 0) return "";
  const std::size_t associated = pairs->gt.size();
  *pairs = sevo::fromGroundTruthFrame(*pairs, static_cast<std::size_t>(args.first_frame));
  if (pairs->gt.size() < 3)
    return "--first-frame " + std::to_string(args.first_frame) + " leaves " + std::to_string(pairs->gt.size()) +
           " of " + std::to_string(associated) + " associated pairs; need at least 3";
  *description += "; evaluated from ground-truth frame " + std::to_string(args.first_frame) + " on (" +
                  std::to_string(pairs->gt.size()) + " of " + std::to_string(associated) + " pairs)";
  return "";
}

/// scale_along_path.png: each stretch's scale over the whole path's, at the stretch's middle.
std::string writeScalePlot(const Arguments& args, const sevo::TrajectoryEvaluation& evaluation) {
  if (evaluation.scale_along_path.stretches.empty() || !(evaluation.path_scale > 0.0)) return "";
  sevo::PlotSeries series;
  series.label = "estimate";
  for (const sevo::ScaleStretch& stretch : evaluation.scale_along_path.stretches) {
    series.x.push_back(0.5 * (stretch.from_m + stretch.to_m));
    series.y.push_back(stretch.scale / evaluation.path_scale);
  }
  sevo::LinePlotOptions plot;
  plot.title = "Scale along the path (per " + sevo::tickLabel(args.options.scale_stretch_m, 1.0) +
               " m): " + fs::path(args.est_path).filename().string();
  plot.x_label = "true distance along the path (m)";
  plot.y_label = "travel / true travel, over the whole path's";
  plot.y_from_zero = false;
  const std::string png = (fs::path(args.output) / "scale_along_path.png").string();
  if (!cv::imwrite(png, sevo::renderLinePlot({series}, plot))) return png + ": cannot write the plot";
  return "";
}

std::string writeOutputs(const Arguments& args, const sevo::EvaluationSources& sources, const sevo::PosePairs& pairs,
                         const sevo::TrajectoryEvaluation& evaluation, const std::string& markdown) {
  std::error_code code;
  fs::create_directories(args.output, code);
  if (code) return args.output + ": cannot create the output directory (" + code.message() + ")";
  const fs::path dir(args.output);
  std::string error = sevo::writeTextFile((dir / "evaluation.md").string(), markdown);
  if (error.empty())
    error = sevo::writeTextFile((dir / "evaluation.json").string(), sevo::evaluationJson(sources, evaluation, args.options));
  if (!error.empty()) return error;

  std::vector<Eigen::Vector3d> aligned;
  for (const Eigen::Isometry3d& pose : pairs.est) aligned.push_back(evaluation.sim3_ate.alignment * pose.translation());
  sevo::TopDownPlotOptions plot;
  plot.title = "Top-down view (x-z): " + fs::path(args.est_path).filename().string() + " vs " +
               fs::path(args.gt_path).filename().string();
  plot.est_label = "estimate, Sim(3)-aligned";
  const std::string png = (dir / "trajectory_top_down.png").string();
  if (!cv::imwrite(png, sevo::renderTopDownPlot(sevo::positionsOf(pairs.gt), aligned, plot)))
    return png + ": cannot write the plot";
  return writeScalePlot(args, evaluation);
}

}  // namespace

int main(int argc, char** argv) {
  Arguments args;
  if (argc == 2 && (std::string(argv[1]) == "--help" || std::string(argv[1]) == "-h")) {
    std::cout << kUsage;
    return 0;
  }
  std::string error = parseArguments(argc, argv, &args);
  if (!error.empty()) {
    std::cerr << "evaluate_trajectory: " << error << "\n" << kUsage;
    return 2;
  }
  sevo::Trajectory gt, est;
  sevo::EvaluationSources sources;
  sevo::PosePairs pairs;
  sevo::TrajectoryEvaluation evaluation;
  sevo::EstimateRecords records;
  error = readInputs(args, &gt, &est, &sources);
  if (error.empty() && !args.keyframes.empty()) error = sevo::readKeyframeFrames(args.keyframes, &records.keyframe_frames);
  if (error.empty() && !args.tracked_motions.empty()) error = sevo::readTrackedMotions(args.tracked_motions, &records.tracked_motions);
  if (error.empty()) error = associate(args, gt, est, &pairs, &sources.association);
  if (error.empty()) error = keepFromFirstFrame(args, &pairs, &sources.association);
  if (error.empty()) error = sevo::evaluateTrajectory(pairs, args.options, records, &evaluation);
  if (!error.empty()) {
    std::cerr << "evaluate_trajectory: " << error << "\n";
    return 1;
  }
  const std::string markdown = sevo::evaluationMarkdown(sources, evaluation, args.options);
  std::cout << markdown;
  error = writeOutputs(args, sources, pairs, evaluation, markdown);
  if (!error.empty()) {
    std::cerr << "evaluate_trajectory: " << error << "\n";
    return 1;
  }
  std::cout << "\nWrote " << (fs::path(args.output) / "evaluation.md").string() << ", evaluation.json, trajectory_top_down.png"
            << (evaluation.scale_along_path.stretches.empty() ? "" : " and scale_along_path.png") << "\n";
  return 0;
}
