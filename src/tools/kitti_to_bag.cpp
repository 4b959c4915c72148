// Converts a KITTI odometry sequence folder into a rosbag that plays into launch/semantic_edge_vo.launch:
// /camera/image_rect (+ complete /camera/camera_info), the semantic topics, /ground_truth/pose.
//   kitti_to_bag --sequence DIR --output BAG [--camera 0|2] [--poses FILE] [--semantics-labels DIR]
//                [--semantics-bitmask DIR] [--start-time T] [--quiet]
// Topics and formats: README (Running on a bag) and docs/synthetic_sequences.md.
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>

#include "semantic_edge_vo/support/command_line.h"
#include "semantic_edge_vo/support/progress_bar.h"
#include "semantic_edge_vo/ros/bags/kitti_bag_conversion.h"

namespace sevo = semantic_edge_vo;

namespace {

const char* const kUsage = R"(usage: kitti_to_bag --sequence DIR --output BAG [options]
  --sequence DIR           KITTI odometry folder: calib.txt, times.txt, image_0/ or image_2/ (%06d.png)
  --output BAG             bag to write (replaced)
  --camera 0|2             0: image_0, grayscale (mono8, P0); 2: image_2, colour (bgr8, P2). Default 0
  --poses FILE             ground truth of camera 0, KITTI poses (12 numbers a line, one line per frame),
                           written on /ground_truth/pose (moved to camera 2 with --camera 2)
  --semantics-labels DIR   %06d.png class labels: 8-bit, 1 channel (class index) or 4 channels
                           (class index, confidence x 255, ...) -> /camera/semantics/class_labels
  --semantics-bitmask DIR  %06d.png edge bitmasks: 8-bit, 4 channels (class bits 0-7, 8-15, 16-23,
                           edge strength x 255) -> /camera/semantics/edge_bitmask
  --start-time T           stamp of time 0 of times.txt, s (default 1600000000)
  --quiet                  no progress bar
)";

/// Empty on success, otherwise what is wrong with the command line.
std::string parseArguments(int argc, char** argv, sevo::KittiBagOptions* options, bool* quiet) {
  std::string camera, start_time;
  const std::string error =
      sevo::parseFlags(argc, argv,
                       {{"--sequence", &options->sequence}, {"--output", &options->output}, {"--poses", &options->poses},
                        {"--semantics-labels", &options->class_labels}, {"--semantics-bitmask", &options->edge_bitmask},
                        {"--camera", &camera}, {"--start-time", &start_time}},
                       {{"--quiet", quiet}});
  if (!error.empty()) return error;
  if (!camera.empty()) {
    if (camera != "0" && camera != "2") return "--camera takes 0 or 2";
    options->camera = std::stoi(camera);
  }
  if (const std::string bad = sevo::parseNumber("--start-time", start_time, &options->start_time); !bad.empty()) return bad;
  if (!(options->start_time > 0.0)) return "--start-time takes a positive time, s";
  if (options->sequence.empty()) return "--sequence is required";
  if (options->output.empty()) return "--output is required";
  return "";
}

}  // namespace

int main(int argc, char** argv) {
  sevo::KittiBagOptions options;
  bool quiet = false;
  if (argc > 1 && (std::string(argv[1]) == "--help" || std::string(argv[1]) == "-h")) {
    std::cout << kUsage;
    return 0;
  }
  if (const std::string error = parseArguments(argc, argv, &options, &quiet); !error.empty()) {
    std::cerr << "kitti_to_bag: " << error << "\n" << kUsage;
    return 2;
  }
  const auto start = std::chrono::steady_clock::now();
  std::unique_ptr<sevo::ProgressBar> progress;
  std::size_t frames = 0;
  const std::string error = sevo::writeKittiBag(options, [&](std::size_t done, std::size_t total) {
    if (!progress) progress = std::make_unique<sevo::ProgressBar>(static_cast<int>(total), !quiet);
    progress->update(static_cast<int>(done));
    frames = done;
  });
  if (!error.empty()) {
    std::cerr << (frames > 0 ? "\n" : "") << "kitti_to_bag: " << error << "\n";
    return 1;
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::cerr << "kitti_to_bag: wrote " << frames << " frames of " << options.sequence << " (camera " << options.camera
            << ") to " << options.output << ", " << std::filesystem::file_size(options.output) / 1e6 << " MB, in "
            << seconds << " s\n";
  return 0;
}
