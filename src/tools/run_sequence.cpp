// Runs the odometry offline, deterministically, on a KITTI odometry folder or a synthetic sequence.
//   run_sequence --sequence DIR --output OUT [--field snnf|onnf|annf|none]
//       [--intake canny|fused|semantic_edges] [--segmenter-model PATH] [--frames N] [--quiet]
// Writes OUT/poses_kitti.txt (one line per input frame, camera-to-world of camera 0, frame 0 at
// identity), OUT/poses_tum.txt, OUT/timing.txt (per frame and stage, ms) and prints a summary.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include "semantic_edge_vo/robust_statistics.h"
#include "semantic_edge_vo/class_table.h"
#include "semantic_edge_vo/odometry.h"
#include "semantic_edge_vo/progress_bar.h"
#include "semantic_edge_vo/sequence_input.h"
#include "semantic_edge_vo/trajectory_io.h"

using namespace semantic_edge_vo;

namespace {

struct Arguments {
  std::string sequence, output, field = "snnf", intake = "canny", segmenter_model;
  int frames = 0;
  bool quiet = false;
};

std::string parse(int argc, char** argv, Arguments* args) {
  for (int i = 1; i < argc; ++i) {
    const std::string flag = argv[i];
    if (flag == "--quiet") {
      args->quiet = true;
      continue;
    }
    if (i + 1 >= argc) return flag + " needs a value";
    const std::string value = argv[++i];
    if (flag == "--sequence") args->sequence = value;
    else if (flag == "--output") args->output = value;
    else if (flag == "--field") args->field = value;
    else if (flag == "--intake") args->intake = value;
    else if (flag == "--segmenter-model") args->segmenter_model = value;
    else if (flag == "--frames") args->frames = std::atoi(value.c_str());
    else return "unknown flag " + flag;
  }
  if (args->sequence.empty() || args->output.empty()) return "--sequence DIR and --output OUT are required";
  return {};
}


}  // namespace

int main(int argc, char** argv) {
  Arguments args;
  std::string error = parse(argc, argv, &args);
  FrameBuilderOptions frame_options;
  if (error.empty() && !parseIntakeMode(args.intake, &frame_options.intake.mode))
    error = "--intake must be canny, fused or semantic_edges (got '" + args.intake + "')";
  frame_options.use_field = args.field != "none";
  if (error.empty() && frame_options.use_field && !parseFieldKind(args.field, &frame_options.field.kind))
    error = "--field must be snnf, onnf, annf or none (got '" + args.field + "')";
  OdometryOptions odometry_options;
  if (error.empty()) error = frame_options.validate();
  if (error.empty()) error = odometry_options.validate();
  if (!error.empty()) {
    std::fprintf(stderr, "run_sequence: %s\n(usage: see the comment at the top of src/tools/run_sequence.cpp)\n", error.c_str());
    return 2;
  }
  const ClassTable classes = ClassTable::cityscapes();
  SequenceInput input;
  error = input.open(args.sequence, frame_options.intake.mode, args.segmenter_model, classes.size());
  if (!error.empty()) {
    std::fprintf(stderr, "run_sequence: %s\n", error.c_str());
    return 1;
  }
  std::filesystem::create_directories(args.output);
  const int frames = args.frames > 0 ? std::min<int>(args.frames, static_cast<int>(input.size())) : static_cast<int>(input.size());
  std::printf("run_sequence: %s, %d frames, %dx%d, intake %s, field %s\n", args.sequence.c_str(), frames,
              input.camera().width, input.camera().height, args.intake.c_str(), args.field.c_str());

  const FrameBuilder builder(frame_options, input.camera(), classes.names());
  Odometry odometry(odometry_options, input.camera());
  std::vector<FramePose> poses;
  std::vector<double> intake_ms(static_cast<std::size_t>(frames), 0.0), segmenter_ms(static_cast<std::size_t>(frames), 0.0);
  ProgressBar progress(frames, !args.quiet);
  for (int i = 0; i < frames; ++i) {
    cv::Mat gray;
    ClassEvidence evidence;
    error = input.read(static_cast<std::size_t>(i), &gray, &evidence);
    if (!error.empty()) {
      std::fprintf(stderr, "\nrun_sequence: frame %d: %s\n", i, error.c_str());
      return 1;
    }
    segmenter_ms[static_cast<std::size_t>(i)] = input.lastSegmenterMs();
    const auto start = std::chrono::steady_clock::now();
    ExtractionError extraction;
    const auto frame = builder.build(i, input.time(static_cast<std::size_t>(i)), gray, evidence, &extraction);
    if (!frame) {
      std::fprintf(stderr, "\nrun_sequence: frame %d: %s: %s\n", i, extraction.reason.c_str(), extraction.detail.c_str());
      return 1;
    }
    intake_ms[static_cast<std::size_t>(i)] = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    for (FramePose& pose : odometry.process(frame)) poses.push_back(pose);
    progress.update(i + 1);
  }
  for (FramePose& pose : odometry.flush()) poses.push_back(pose);
  std::sort(poses.begin(), poses.end(), [](const FramePose& a, const FramePose& b) { return a.index < b.index; });

  Trajectory trajectory;
  std::ostringstream timing;
  timing << "# frame segmenter_ms intake_ms tracking_ms mapping_ms total_ms trusted state keyframe\n";
  int trusted = 0, keyframes = 0, lost = 0;
  std::vector<double> totals;
  for (const FramePose& pose : poses) {
    trajectory.poses.push_back(pose.T_world_cam);
    trajectory.stamps.push_back(pose.time);
    const std::size_t i = static_cast<std::size_t>(pose.index);
    const double total = intake_ms[i] + pose.tracking_ms + pose.mapping_ms;
    totals.push_back(total);
    timing << pose.index << ' ' << segmenter_ms[i] << ' ' << intake_ms[i] << ' ' << pose.tracking_ms << ' ' << pose.mapping_ms
           << ' ' << total << ' ' << pose.trusted << ' ' << toString(pose.state) << ' ' << pose.keyframe << '\n';
    trusted += pose.trusted;
    keyframes += pose.keyframe;
    lost += pose.state == OdometryState::kLost;
  }
  for (const std::string& written :
       {writeKittiPoses(args.output + "/poses_kitti.txt", trajectory), writeTumTrajectory(args.output + "/poses_tum.txt", trajectory),
        writeTextFile(args.output + "/timing.txt", timing.str())})
    if (!written.empty()) {
      std::fprintf(stderr, "run_sequence: %s\n", written.c_str());
      return 1;
    }
  std::printf("run_sequence: %d frames, %d with a trusted pose, %d lost, %d keyframes; median per frame %.1f ms "
              "(intake %.1f, tracking %.1f, mapping %.1f)\n",
              frames, trusted, lost, keyframes, median(totals), median(intake_ms),
              median([&] { std::vector<double> v; for (auto& p : poses) v.push_back(p.tracking_ms); return v; }()),
              median([&] { std::vector<double> v; for (auto& p : poses) v.push_back(p.mapping_ms); return v; }()));
  std::printf("run_sequence: wrote %s/poses_kitti.txt, poses_tum.txt, timing.txt\n", args.output.c_str());
  return 0;
}
