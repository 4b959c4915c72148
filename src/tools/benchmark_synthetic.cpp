// Speed of the synthetic sequence generator on one core: renders frames (all channels) and encodes
// them as the sequence writer does (PNG, in memory), and prints frames per second of each.
//   benchmark_synthetic [--scene city|village|highway] [--frames N] [--seed S] [--no-semantics]
#include <chrono>
#include <ctime>
#include <cstdio>
#include <iostream>
#include <string>

#include <opencv2/core/utility.hpp>

#include "semantic_edge_vo/common/class_table.h"
#include "semantic_edge_vo/support/command_line.h"
#include "semantic_edge_vo/synthetic/sequence_formats.h"
#include "semantic_edge_vo/synthetic/synthetic_sequence.h"

using namespace semantic_edge_vo::synthetic;

namespace {

const char* const kUsage = "usage: benchmark_synthetic [--scene city|village|highway] [--frames N] [--seed S] [--no-semantics]\n";

/// CPU time of this thread, s: unlike wall time it does not grow when other processes share the core.
double cpuSeconds() {
  timespec now{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &now);
  return static_cast<double>(now.tv_sec) + 1e-9 * static_cast<double>(now.tv_nsec);
}

}  // namespace

int main(int argc, char** argv) {
  namespace sevo = semantic_edge_vo;
  if (sevo::printUsageIfAsked(argc, argv, kUsage)) return 0;
  SceneType scene = SceneType::kCity;
  int frames = 50;
  std::uint64_t seed = 1;
  std::string scene_text, frames_text, seed_text;
  bool no_semantics = false;
  std::string error = sevo::parseFlags(argc, argv, {{"--scene", &scene_text}, {"--frames", &frames_text}, {"--seed", &seed_text}},
                                       {{"--no-semantics", &no_semantics}});
  if (error.empty() && !scene_text.empty() && !parseSceneType(scene_text, &scene)) error = "--scene takes city, village or highway";
  if (error.empty()) error = sevo::parseNumber("--frames", frames_text, &frames);
  if (error.empty() && frames < 1) error = "--frames takes a positive count";
  if (error.empty()) error = sevo::parseNumber("--seed", seed_text, &seed);
  if (!error.empty()) {
    std::cerr << "benchmark_synthetic: " << error << "\n" << kUsage;
    return 2;
  }
  const bool semantics = !no_semantics;
  cv::setNumThreads(1);  // one core, as the requirement states it
  SyntheticSequenceOptions options = SyntheticSequenceOptions::forScene(scene, seed);
  options.semantics = semantics;
  SyntheticSequence sequence(options);
  const semantic_edge_vo::ClassTable classes = semantic_edge_vo::ClassTable::cityscapes();

  double render_seconds = 0.0, encode_seconds = 0.0;
  std::size_t bytes = 0;
  const auto wall_start = std::chrono::steady_clock::now();
  for (int i = 0; i < frames; ++i) {
    double start = cpuSeconds();
    const SyntheticFrame frame = sequence.frame(i);
    render_seconds += cpuSeconds() - start;
    start = cpuSeconds();
    for (const auto& file : encodeFrame(frame, semantics, classes).files) bytes += file.second.size();
    encode_seconds += cpuSeconds() - start;
  }
  const double wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  const double mb_per_frame = bytes / 1e6 / frames;
  std::printf("scene %s, %d frames of %dx%d, one thread; CPU time of that thread (wall time: %.1f s)\n",
              toString(scene), frames, options.camera.width, options.camera.height, wall_seconds);
  std::printf("render (all channels): %6.1f frames/s  (%.1f ms/frame)\n", frames / render_seconds,
              1e3 * render_seconds / frames);
  std::printf("PNG encoding:          %6.1f frames/s  (%.1f ms/frame)\n", frames / encode_seconds,
              1e3 * encode_seconds / frames);
  std::printf("render + encoding:     %6.1f frames/s\n", frames / (render_seconds + encode_seconds));
  std::printf("files: %.2f MB/frame, %.2f GB per 1000 frames\n", mb_per_frame, mb_per_frame);
  return 0;
}
