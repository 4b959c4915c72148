// Runs the segmentation network over a KITTI odometry folder once and saves its class labels, so that
// the odometry can use them later without the network: offline (run_sequence --intake fused reads
// DIR/class_probability/) and live (kitti_to_bag --semantics-labels), where on 2 cores the network
// and the odometry do not both keep up with the camera. Usage: kUsage below.
#include <cstdio>
#include <filesystem>
#include <vector>

#include "semantic_edge_vo/common/class_table.h"
#include "semantic_edge_vo/support/command_line.h"
#include "semantic_edge_vo/config/graph_config.h"
#include "semantic_edge_vo/sequences/kitti_sequence.h"
#include "semantic_edge_vo/support/progress_bar.h"
#include "semantic_edge_vo/common/robust_statistics.h"
#include "semantic_edge_vo/sequences/semantic_map_files.h"
#include "semantic_edge_vo/sequences/sequence_input.h"

using namespace semantic_edge_vo;

namespace {

const char* const kUsage = R"(usage: segment_sequence --sequence DIR --segmenter-model PATH [--output OUT] [--config FILE] [--quiet]
Runs the segmentation network (OpenCV dnn; e.g. ENet's model-best.opencv.net) on every frame of a
KITTI odometry folder (image_2/ colour frames when present, else image_0/) and writes its labels to
OUT/%06d.png (default OUT: DIR/class_probability), one 16-bit channel a pixel: the most probable
class + 256 x its probability x 255 (the labels form, half the bytes of the synthetic sequences'
4-channel layout, which is read too). With OUT the default, run_sequence --intake fused then reads them instead of running the
network; kitti_to_bag --semantics-labels OUT puts them in a bag for the launch file's fused intake
(class_format labels). OUT must not hold files yet. --config reads the segmenter block and the class
table (edge_intake/classes) of a file laid out like config/semantic_edge_vo.yaml.
)";

struct Arguments {
  std::string sequence, model, output, config;
  bool quiet = false;
};

std::string parse(int argc, char** argv, Arguments* args) {
  const std::string error = parseFlags(argc, argv,
                                       {{"--sequence", &args->sequence}, {"--segmenter-model", &args->model},
                                        {"--output", &args->output}, {"--config", &args->config}},
                                       {{"--quiet", &args->quiet}});
  if (!error.empty()) return error;
  if (args->sequence.empty() || args->model.empty()) return "--sequence DIR and --segmenter-model PATH are required";
  if (args->output.empty()) args->output = args->sequence + "/class_probability";
  return {};
}

}  // namespace

int main(int argc, char** argv) {
  if (printUsageIfAsked(argc, argv, kUsage)) return 0;
  Arguments args;
  GraphConfig config;  // the segmenter's options and the class table: built-in (ENet, Cityscapes), then the config file's
  std::string error = parse(argc, argv, &args);
  if (error.empty()) error = loadGraphConfig(args.config, &config);
  SegmenterOptions& segmenter = config.segmenter;
  const ClassTable& classes = config.classes;
  if (!error.empty()) {
    std::fprintf(stderr, "segment_sequence: %s\n%s", error.c_str(), kUsage);
    return 2;
  }
  segmenter.model_path = args.model;
  SequenceInput input;
  error = input.open(args.sequence, IntakeMode::kFused, segmenter, classes.size());
  if (!error.empty()) {
    std::fprintf(stderr, "segment_sequence: %s\n", error.c_str());
    return 1;
  }
  // A synthetic sequence's class_probability/ holds its simulated network: never overwritten unasked.
  if (std::filesystem::is_directory(args.output) && !std::filesystem::is_empty(args.output)) {
    std::fprintf(stderr, "segment_sequence: %s exists and is not empty: remove it, or choose another --output\n", args.output.c_str());
    return 1;
  }
  std::filesystem::create_directories(args.output);
  const int frames = static_cast<int>(input.size());
  std::printf("segment_sequence: %s, %d frames, %d classes -> %s\n", args.sequence.c_str(), frames, classes.size(),
              args.output.c_str());
  ProgressBar progress(frames, !args.quiet);
  std::vector<double> segmenter_ms;
  for (int i = 0; i < frames; ++i) {
    cv::Mat gray;
    ClassEvidence evidence;
    error = input.read(static_cast<std::size_t>(i), &gray, &evidence);
    if (error.empty()) error = writeClassLabelsPng(kittiFramePath(args.output, static_cast<std::size_t>(i)), evidence.values);
    if (!error.empty()) {
      std::fprintf(stderr, "\nsegment_sequence: frame %d: %s\n", i, error.c_str());
      return 1;
    }
    segmenter_ms.push_back(input.lastSegmenterMs());
    progress.update(i + 1);
  }
  std::printf("segment_sequence: wrote %d label images to %s; the network took %.1f ms per frame (median)\n", frames,
              args.output.c_str(), frames > 0 ? median(segmenter_ms) : 0.0);
  return 0;
}
