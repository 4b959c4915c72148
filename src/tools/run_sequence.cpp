// Runs the odometry offline, deterministically, on a KITTI odometry folder or a synthetic sequence
// (usage: kUsage below, printed by --help).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <future>
#include <optional>
#include <set>
#include <sstream>
#include <thread>

#include "semantic_edge_vo/common/class_table.h"
#include "semantic_edge_vo/support/command_line.h"
#include "semantic_edge_vo/support/host_cpu.h"
#include "semantic_edge_vo/config/graph_config.h"
#include "semantic_edge_vo/edges/class_map_carrier.h"
#include "semantic_edge_vo/eval/keyframe_depth_report.h"
#include "semantic_edge_vo/backend/odometry.h"
#include "semantic_edge_vo/backend/trajectory_record.h"
#include "semantic_edge_vo/support/progress_bar.h"
#include "semantic_edge_vo/common/robust_statistics.h"
#include "semantic_edge_vo/sequences/sequence_input.h"
#include "semantic_edge_vo/common/tracked_motions.h"
#include "semantic_edge_vo/common/trajectory_io.h"
#include "semantic_edge_vo/ros/bags/bag_sequence.h"

using namespace semantic_edge_vo;

namespace {

struct Arguments {
  std::string sequence, output, field, intake, segmenter_model, config;  ///< field, intake: empty = config's
  std::string bag, topic;  ///< a recording instead of a folder
  std::string frames_text, latency_text, rate_text, camera_height_text;
  int frames = 0;  ///< 0: all
  int class_map_latency = 0;  ///< 0: every frame has its own class map
  double rate = 0.0;          ///< frames a second at most (a camera's rate); 0: as fast as it can
  double camera_height = 0.0; ///< m above the road (metric scale); 0: the config's
  bool quiet = false;
  bool parallel = false;  ///< mapping on its own thread (the live default) instead of after each frame
  bool rectify = false;   ///< --bag: undistort with camera_info first
};

std::string parse(int argc, char** argv, Arguments* args) {
  const std::string error = parseFlags(argc, argv,
                                       {{"--sequence", &args->sequence}, {"--output", &args->output}, {"--field", &args->field},
                                        {"--intake", &args->intake}, {"--segmenter-model", &args->segmenter_model},
                                        {"--config", &args->config}, {"--frames", &args->frames_text},
                                        {"--class-map-latency", &args->latency_text}, {"--rate", &args->rate_text},
                                        {"--camera-height", &args->camera_height_text}, {"--bag", &args->bag}, {"--topic", &args->topic}},
                                       {{"--quiet", &args->quiet}, {"--parallel", &args->parallel}, {"--rectify", &args->rectify}});
  if (!error.empty()) return error;
  if (const std::string bad = parseNumber("--frames", args->frames_text, &args->frames); !bad.empty()) return bad;
  if (args->frames < 0) return "--frames takes a count >= 0 (0: all)";
  if (const std::string bad = parseNumber("--class-map-latency", args->latency_text, &args->class_map_latency); !bad.empty()) return bad;
  if (args->class_map_latency < 0) return "--class-map-latency takes a frame count >= 0";
  if (const std::string bad = parseNumber("--rate", args->rate_text, &args->rate); !bad.empty()) return bad;
  if (args->rate < 0.0) return "--rate takes frames a second >= 0 (0: as fast as it can)";
  if (const std::string bad = parseNumber("--camera-height", args->camera_height_text, &args->camera_height); !bad.empty()) return bad;
  if (!args->camera_height_text.empty() && !(args->camera_height > 0.0)) return "--camera-height takes metres > 0";
  if (args->output.empty()) return "--output OUT is required";
  if (args->sequence.empty() == args->bag.empty()) return "give --sequence DIR or --bag FILE --topic TOPIC (one of them)";
  if (!args->bag.empty() && args->topic.empty()) return "--bag needs --topic (the image topic)";
  if (args->rectify && args->bag.empty()) return "--rectify applies to --bag only (a KITTI folder is rectified)";
  return {};
}

/// --bag: the recording's images as a KITTI folder in OUT/bag_sequence, which becomes the sequence.
std::string sequenceFromBag(Arguments* args) {
  BagSequenceOptions bag;
  bag.bag = args->bag;
  bag.topic = args->topic;
  bag.output = args->output + "/bag_sequence";
  bag.rectify = args->rectify;
  std::optional<ProgressBar> progress;  // its total comes with the first image
  std::size_t frames = 0, skipped = 0;
  const std::string error = writeSequenceFromBag(bag, [&](std::size_t done, std::size_t total) {
    if (!progress) progress.emplace(static_cast<int>(total), !args->quiet, "images");
    progress->update(static_cast<int>(done));
  }, &frames, &skipped);
  if (!error.empty()) return error;
  std::printf("run_sequence: %zu images from %s on %s%s\n", frames, args->bag.c_str(), args->topic.c_str(),
              skipped ? (", " + std::to_string(skipped) + " skipped (stamp not after the previous)").c_str() : "");
  args->sequence = bag.output;
  return "";
}

/// A depth file the keyframe depth check cannot use ends the check, not the run.
void stopOnError(const std::string& error, std::optional<KeyframeDepthReport>* report) {
  if (error.empty()) return;
  std::fprintf(stderr, "\nrun_sequence: keyframe depth check stopped: %s\n", error.c_str());
  report->reset();
}

/// The command line's choices over the config's.
std::string applyFlags(const Arguments& args, GraphConfig* options) {
  if (!args.intake.empty() && !parseIntakeMode(args.intake, &options->frame.intake.mode))
    return "--intake must be canny, fused or semantic_edges (got '" + args.intake + "')";
  if (!args.field.empty()) {
    options->frame.use_field = args.field != "none";
    if (options->frame.use_field && !parseFieldKind(args.field, &options->frame.field.kind))
      return "--field must be snnf, onnf, annf or none (got '" + args.field + "')";
  }
  if (!args.segmenter_model.empty()) options->segmenter.model_path = args.segmenter_model;
  if (args.camera_height > 0.0) options->odometry.road.camera_height = args.camera_height;
  options->summary += "\n  command line: intake " + args.intake + ", field " + args.field + ", segmenter model " +
                      args.segmenter_model + ", camera height " + args.camera_height_text + " (empty: as above)";
  std::string error = options->frame.validate();
  return error.empty() ? options->odometry.validate() : error;
}

const char* const kUsage = R"(usage: run_sequence (--sequence DIR | --bag FILE --topic TOPIC [--rectify]) --output OUT [--field snnf|onnf|annf|none]
           [--intake canny|fused|semantic_edges] [--segmenter-model PATH] [--config FILE] [--frames N]
           [--class-map-latency N] [--parallel] [--rate HZ] [--camera-height METRES] [--quiet]
Runs the odometry offline on a KITTI odometry folder (image_0/, calib.txt, times.txt), a synthetic
sequence, or the images of TOPIC in a bag (sensor_msgs/Image or CompressedImage, rectified unless
--rectify, with camera_info beside the topic; written to OUT/bag_sequence/ for the run and removed), frames as fast as it can, deterministically: mapping runs after each frame (the
config's tracking/mapping_mode is the live graph's). --parallel runs mapping on its own thread, as
the live graph does by default: tracking never waits for it, and the trajectory depends on timing.
--rate HZ feeds the frames no faster than HZ a second, as a camera would (the time waiting is not
counted in the figures). --config reads a file laid out like config/semantic_edge_vo.yaml
(the nodelets' parameters; a key no option reads is an error); the flags override it; without it
every option has its default, which the shipped config equals. Writes OUT/poses_kitti.txt
(one line per input frame, camera-to-world of camera 0, frame 0 at identity), OUT/poses_tum.txt,
OUT/poses_flags.txt (per pose line: trusted 0 marks a prediction, not an estimate), OUT/timing.txt (per frame and stage, ms), OUT/parameters.txt (every option used),
OUT/tracked_motions.txt (each trusted frame's motion from its keyframe with the tracker's covariance, as
published: evaluate_trajectory --tracked-motions checks it against ground truth) and prints a summary.
On a synthetic sequence with true depths (DIR/depth/) it also checks every keyframe's point depths
against them (not with --parallel): OUT/keyframe_depths.txt and a summary line.
--class-map-latency N replays a live segmenter N frames slower than the camera (fused and
semantic_edges intakes): only every Nth frame's class map is made, each is ready N frames later, and
every frame uses the newest ready map carried to it by the optical flow (as the EdgeIntake nodelet
does with class_maps: newest); frames before the first map get Canny edges of no class.
timing.txt's class_map_age column gives each frame's map age in frames (-1: none).
--camera-height METRES (the camera's optical centre above the road; KITTI: 1.65) puts the odometry in
metres: the road under each keyframe (road-class points, or with the Canny intake the points in the
lane ahead) holds its scale; timing.txt's scale and scale_confidence columns say where it was measured.
)";

/// What a run produced: the poses in frame order and its times.
struct RunRecord {
  std::vector<FramePose> poses;
  std::vector<double> intake_ms, segmenter_ms;  ///< per frame
  std::vector<int> class_map_age;               ///< per frame, frames (-1: no class map)
  double processing_s = 0.0;    ///< wall time of intake + odometry, without reading the files
  double odometry_s = 0.0;      ///< of the odometry alone (tracking + mapping; live, the intake has its own nodelet)
  double odometry_cpu_s = 0.0;  ///< CPU time of all threads during the odometry: what the code costs, whatever the host
  double stolen_share = -1.0;   ///< of the host's CPU time the hypervisor took during the run (< 0: unknown)
  int mapping_dropped = 0;      ///< frames the parallel mapping dropped from its full queue
};

/// A live segmenter `latency` frames slower than the camera, replayed: it segments frame 0, is done
/// `latency` frames later and takes the newest frame then; each frame uses the newest ready map
/// carried to it (latency 0: every frame its own map).
class ReplayedSegmenter {
 public:
  ReplayedSegmenter(int latency, const ClassMapCarrierOptions& options) : latency_(latency), carrier_(options) {}

  /// The frame's class evidence (replaced by the carried map, or emptied when none is ready) and its
  /// age in frames (-1: none).
  int classesFor(int frame, double time, const cv::Mat& gray, ClassEvidence* evidence) {
    if (latency_ == 0) return 0;
    carrier_.addImage(time, gray);
    if (frame % latency_ == 0) {
      if (segmenting_) carrier_.setClassMap(segmenting_time_, segmenting_map_);
      segmenting_ = true;
      segmenting_time_ = time;
      segmenting_map_ = *evidence;  // each frame reads into new matrices: no copy needed
      segmenting_frame_ = frame;
    }
    double age = 0.0;
    ClassEvidence carried;
    if (!carrier_.carryTo(time, &carried, &age)) {
      evidence->values.release();
      return -1;
    }
    *evidence = carried;
    return frame - (segmenting_frame_ - latency_);
  }

 private:
  int latency_;
  ClassMapCarrier carrier_;
  bool segmenting_ = false;
  double segmenting_time_ = 0.0;
  int segmenting_frame_ = 0;
  ClassEvidence segmenting_map_;
};

/// One frame as SequenceInput::read gives it.
struct InputFrame {
  std::string error;
  cv::Mat gray;
  ClassEvidence evidence;
  double segmenter_ms = 0.0;
};

/// Reads frame `index` now, or on another thread while the frame before it is processed: decoding
/// the image and label PNGs then takes nothing from the odometry's time. Not with an in-process
/// segmenter, which takes both cores itself and whose time is measured per frame.
std::future<InputFrame> readFrame(SequenceInput& input, int index) {
  const auto read = [&input, index] {
    InputFrame frame;
    frame.error = input.read(static_cast<std::size_t>(index), &frame.gray, &frame.evidence);
    frame.segmenter_ms = input.lastSegmenterMs();
    return frame;
  };
  return std::async(input.segmentsInProcess() ? std::launch::deferred : std::launch::async, read);
}

/// Runs the odometry over the first `frames` frames; `depth_report` (synthetic sequences) checks
/// every keyframe's depths. Returns the error that stopped the run, empty when it ran through.
std::string runFrames(const GraphConfig& options, SequenceInput& input, int frames, const Arguments& args, MappingMode mapping,
                      std::optional<KeyframeDepthReport>* depth_report, RunRecord* record) {
  const int class_map_latency = args.class_map_latency;
  ReplayedSegmenter segmenter(options.frame.intake.mode == IntakeMode::kCanny ? 0 : class_map_latency, options.intake_stream.class_carry);
  const FrameBuilder builder(options.frame, input.camera(), options.classes.names());
  OdometryOptions odometry_options = options.odometry;
  odometry_options.road.road_classes = roadClassBits(builder.classNames());
  Odometry odometry(odometry_options, input.camera(), mapping);
  // In parallel mode a frame's pose is returned before mapping decides whether it becomes a keyframe.
  std::set<int> keyframe_frames;
  const auto takeKeyframes = [&odometry, &keyframe_frames] {
    const std::vector<std::shared_ptr<const KeyframeWindow>> windows = odometry.takeNewWindows();
    for (const auto& window : windows) keyframe_frames.insert(window->frame_index);
    return windows;
  };
  record->intake_ms.assign(static_cast<std::size_t>(frames), 0.0);
  record->segmenter_ms.assign(static_cast<std::size_t>(frames), 0.0);
  record->class_map_age.assign(static_cast<std::size_t>(frames), 0);
  ProgressBar progress(frames, !args.quiet);
  HostCpuTimes host_before, host_after;
  const bool host_known = readHostCpuTimes(&host_before);
  const auto first_frame_at = std::chrono::steady_clock::now();
  std::future<InputFrame> next;
  if (frames > 0) next = readFrame(input, 0);
  for (int i = 0; i < frames; ++i) {
    if (args.rate > 0.0)
      std::this_thread::sleep_until(first_frame_at + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                                         std::chrono::duration<double>(i / args.rate)));
    InputFrame input_frame = next.get();
    if (!input_frame.error.empty()) return "frame " + std::to_string(i) + ": " + input_frame.error;
    if (i + 1 < frames) next = readFrame(input, i + 1);
    cv::Mat& gray = input_frame.gray;
    ClassEvidence& evidence = input_frame.evidence;
    record->segmenter_ms[static_cast<std::size_t>(i)] = input_frame.segmenter_ms;
    const auto start = std::chrono::steady_clock::now();
    record->class_map_age[static_cast<std::size_t>(i)] = segmenter.classesFor(i, input.time(static_cast<std::size_t>(i)), gray, &evidence);
    ExtractionError extraction;
    const auto frame = builder.build(i, input.time(static_cast<std::size_t>(i)), gray, evidence, &extraction);
    if (!frame) return "frame " + std::to_string(i) + ": " + extraction.reason + ": " + extraction.detail;
    record->intake_ms[static_cast<std::size_t>(i)] = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    const auto odometry_start = std::chrono::steady_clock::now();
    const double odometry_cpu_start = processCpuSeconds();
    for (FramePose& pose : odometry.process(frame)) record->poses.push_back(pose);
    const auto windows = takeKeyframes();
    record->odometry_cpu_s += processCpuSeconds() - odometry_cpu_start;
    record->odometry_s += std::chrono::duration<double>(std::chrono::steady_clock::now() - odometry_start).count();
    record->processing_s += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (*depth_report) stopOnError((*depth_report)->update(odometry.activeKeyframe(), windows), depth_report);
    progress.update(i + 1);
  }
  odometry.finishMapping();
  takeKeyframes();
  for (FramePose& pose : odometry.flush()) record->poses.push_back(pose);
  for (FramePose& pose : record->poses) pose.keyframe = keyframe_frames.count(pose.index) > 0;
  record->mapping_dropped = odometry.mappingDropped();
  if (host_known && readHostCpuTimes(&host_after)) record->stolen_share = stolenShare(host_before, host_after);
  if (*depth_report) (*depth_report)->finish(odometry.activeKeyframe());
  std::sort(record->poses.begin(), record->poses.end(), [](const FramePose& a, const FramePose& b) { return a.index < b.index; });
  return "";
}

/// Frame counts by outcome and the median time per frame.
struct RunCounts {
  int trusted = 0, keyframes = 0, lost = 0, untrusted = 0;
  std::vector<double> totals;  ///< ms per frame: intake + tracking + mapping
};

/// The trusted frames' motions from their keyframes, with the tracker's covariance (a map's first
/// frame, which defines it, has none).
std::vector<TrackedMotion> trackedMotionsOf(const std::vector<FramePose>& poses) {
  std::vector<TrackedMotion> motions;
  for (const FramePose& pose : poses) {
    if (!pose.trusted || !pose.tracking.ok || pose.keyframe_frame < 0 || pose.keyframe_frame == pose.index ||
        pose.tracking.covariance.isZero())
      continue;
    TrackedMotion motion;
    motion.frame = static_cast<std::size_t>(pose.index);
    motion.keyframe_frame = static_cast<std::size_t>(pose.keyframe_frame);
    motion.in_metres = pose.scale != ScaleState::kArbitrary;
    motion.T_cam_kf = pose.tracking.T_cam_kf;
    motion.covariance = pose.tracking.covariance;
    motions.push_back(motion);
  }
  return motions;
}

/// Writes the poses, timing.txt, parameters.txt and tracked_motions.txt into `output`; returns the
/// first write error.
std::string writeOutputs(const std::string& output, const RunRecord& record, const std::string& parameters, RunCounts* counts) {
  TrajectoryRecord trajectory;
  std::ostringstream timing;
  timing << "# frame segmenter_ms intake_ms tracking_ms mapping_ms total_ms window_ms iterations trusted state keyframe guess inlier_ratio motion_deviation keyframe_scale class_map_age scale scale_confidence\n";
  for (const FramePose& pose : record.poses) {
    trajectory.add(pose, pose.time);
    const std::size_t i = static_cast<std::size_t>(pose.index);
    const double total = record.intake_ms[i] + pose.tracking_ms + pose.mapping_ms;
    counts->totals.push_back(total);
    timing << pose.index << ' ' << record.segmenter_ms[i] << ' ' << record.intake_ms[i] << ' ' << pose.tracking_ms << ' ' << pose.mapping_ms
           << ' ' << total << ' ' << pose.window_ms << ' ' << pose.tracking.iterations << ' ' << pose.trusted << ' ' << toString(pose.state) << ' ' << pose.keyframe
           << ' ' << pose.tracking.guess << ' ' << pose.tracking.inlierRatio() << ' ' << pose.motion_deviation << ' ' << pose.keyframe_scale
           << ' ' << record.class_map_age[i] << ' ' << toString(pose.scale) << ' ' << pose.scale_confidence << '\n';
    counts->trusted += pose.trusted;
    counts->keyframes += pose.keyframe;
    counts->lost += pose.state == OdometryState::kLost;
    counts->untrusted += pose.state == OdometryState::kUntrusted;
  }
  for (const std::string& written : {trajectory.write(output), writeTextFile(output + "/timing.txt", timing.str()),
                                     writeTextFile(output + "/parameters.txt", parameters),
                                     writeTrackedMotions(output + "/tracked_motions.txt", trackedMotionsOf(record.poses))})
    if (!written.empty()) return written;
  return "";
}

void printSummary(int frames, const RunRecord& record, const RunCounts& counts, MappingMode mapping) {
  // Median of a stage over the frames (or only those where it ran).
  const auto stage = [&](double FramePose::*ms, bool ran_only) {
    std::vector<double> values;
    for (const FramePose& pose : record.poses)
      if (!ran_only || pose.*ms > 0.0) values.push_back(pose.*ms);
    return values.empty() ? 0.0 : median(values);
  };
  std::printf("run_sequence: %d frames, %d with a trusted pose, %d untrusted, %d lost, "
              "%d keyframes; median per frame %.1f ms (intake %.1f, tracking %.1f, mapping %.1f)",
              frames, counts.trusted, counts.untrusted, counts.lost, counts.keyframes, median(counts.totals), median(record.intake_ms),
              stage(&FramePose::tracking_ms, false), stage(&FramePose::mapping_ms, false));
  if (mapping == MappingMode::kParallel)
    std::printf("; mapping on its own thread (not in the total), %d frames dropped from its queue\n", record.mapping_dropped);
  else
    std::printf("; windowed optimisation %.1f ms each (in mapping)\n", stage(&FramePose::window_ms, true));
  std::printf("run_sequence: throughput %.1f frames/s (wall time of intake + odometry over all frames, %.1f s; "
              "files not counted); odometry alone (tracking + mapping) %.1f frames/s\n",
              frames / std::max(record.processing_s, 1e-9), record.processing_s, frames / std::max(record.odometry_s, 1e-9));
  // Wall-time figures move with the host's load (1.5 times within an hour on a shared 2-core VM);
  // the CPU time moves much less (not at all with time stolen by the hypervisor), and the stolen
  // share says how contended the host was.
  std::printf("run_sequence: odometry CPU time %.1f ms a frame (%.2f cores busy on average)", 1e3 * record.odometry_cpu_s / std::max(frames, 1),
              record.odometry_cpu_s / std::max(record.odometry_s, 1e-9));
  if (record.stolen_share >= 0.0) std::printf("; the hypervisor took %.0f %% of the host's CPU time during the run", 100.0 * record.stolen_share);
  std::printf("\n");
}

}  // namespace

int main(int argc, char** argv) {
  if (printUsageIfAsked(argc, argv, kUsage)) return 0;
  Arguments args;
  GraphConfig options;  // built-in defaults, then the config file, then the flags
  std::string error = parse(argc, argv, &args);
  if (error.empty()) error = loadGraphConfig(args.config, &options);
  if (error.empty()) error = applyFlags(args, &options);
  if (!error.empty()) {
    std::fprintf(stderr, "run_sequence: %s\n%s", error.c_str(), kUsage);
    return 2;
  }
  if (!args.bag.empty()) {
    error = sequenceFromBag(&args);
    if (!error.empty()) {
      std::fprintf(stderr, "run_sequence: %s\n", error.c_str());
      return 1;
    }
  }
  const FrameBuilderOptions& frame_options = options.frame;
  SequenceInput input;
  error = input.open(args.sequence, frame_options.intake.mode, options.segmenter, options.classes.size());
  if (!error.empty()) {
    std::fprintf(stderr, "run_sequence: %s\n", error.c_str());
    return 1;
  }
  std::filesystem::create_directories(args.output);
  const int frames = args.frames > 0 ? std::min<int>(args.frames, static_cast<int>(input.size())) : static_cast<int>(input.size());
  const std::string field_name = frame_options.use_field ? toString(frame_options.field.kind) : "none";
  std::printf("run_sequence: %s, %d frames, %dx%d, intake %s, field %s, window optimisation %s, mapping %s%s%s\n",
              args.sequence.c_str(), frames, input.camera().width, input.camera().height, toString(frame_options.intake.mode),
              field_name.c_str(), options.odometry.optimize_window ? "on" : "off", args.parallel ? "parallel" : "deterministic",
              args.config.empty() ? "" : ", config ", args.config.c_str());
  // Synthetic sequences carry their true depths: check every keyframe's point depths against them.
  const std::string depth_folder = args.sequence + "/depth";
  // (Deterministic mapping only: the check reads the mapper's keyframes between frames.)
  const MappingMode mapping = args.parallel ? MappingMode::kParallel : MappingMode::kDeterministic;
  std::optional<KeyframeDepthReport> depth_report;
  if (std::filesystem::is_directory(depth_folder) && mapping == MappingMode::kDeterministic) depth_report.emplace(depth_folder);
  RunRecord record;
  RunCounts counts;
  error = runFrames(options, input, frames, args, mapping, &depth_report, &record);
  if (!error.empty()) {
    std::fprintf(stderr, "\nrun_sequence: %s\n", error.c_str());
    return 1;
  }
  const std::string parameters =
      "# " + (args.config.empty() ? "built-in defaults" : args.config) + ", then the command line:" + options.summary + "\n";
  error = writeOutputs(args.output, record, parameters, &counts);
  if (error.empty() && depth_report) error = writeTextFile(args.output + "/keyframe_depths.txt", depth_report->table());
  if (!error.empty()) {
    std::fprintf(stderr, "run_sequence: %s\n", error.c_str());
    return 1;
  }
  printSummary(frames, record, counts, mapping);
  if (!args.bag.empty()) std::filesystem::remove_all(args.sequence);
  if (depth_report) std::printf("run_sequence: keyframe depths against the sequence's true depths: %s\n", depth_report->summary().c_str());
  std::printf("run_sequence: wrote %s/poses_kitti.txt, poses_tum.txt, poses_flags.txt, timing.txt, parameters.txt, tracked_motions.txt%s\n", args.output.c_str(),
              depth_report ? ", keyframe_depths.txt" : "");
  return 0;
}
