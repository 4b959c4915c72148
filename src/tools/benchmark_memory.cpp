// Memory of a long drive: renders a synthetic drive in memory (no files) frame by frame into the
// odometry (Canny edges, SNNF, the shipped defaults) and prints the process's resident memory as it
// goes, then that at frame 1000 against that at the last frame: the map and every queue must stay
// bounded however long the car drives.
//   benchmark_memory [--scene city|village|highway] [--frames N] [--seed S] [--parallel] [--report-every N]
#include <cstdio>
#include <fstream>
#include <iostream>
#include <string>

#include "semantic_edge_vo/backend/odometry.h"
#include "semantic_edge_vo/common/class_table.h"
#include "semantic_edge_vo/common/freed_memory.h"
#include "semantic_edge_vo/frontend/odometry_frame.h"
#include "semantic_edge_vo/support/command_line.h"
#include "semantic_edge_vo/synthetic/synthetic_sequence.h"

using namespace semantic_edge_vo;

namespace {

const char* const kUsage =
    "usage: benchmark_memory [--scene city|village|highway] [--frames N] [--seed S] [--parallel] [--report-every N]\n"
    "Streams a synthetic drive (rendered in memory) into the odometry and prints its resident memory\n"
    "every N frames (default 1000) and at the end, against frame 1000 (frames default 10000; mapping\n"
    "deterministic unless --parallel).\n";

/// This process's resident memory (VmRSS), MiB; negative when /proc cannot tell.
double residentMiB() {
  std::ifstream status("/proc/self/status");
  std::string key;
  while (status >> key) {
    if (key == "VmRSS:") {
      double kib = -1.0;
      status >> kib;
      return kib / 1024.0;
    }
    status.ignore(1 << 12, '\n');
  }
  return -1.0;
}

/// Resident memory once the allocator has given back the free pages it keeps for reuse (in every
/// thread's arena), MiB: what the code holds.
double trimmedResidentMiB() {
  releaseFreedMemory();
  return residentMiB();
}

}  // namespace

int main(int argc, char** argv) {
  if (printUsageIfAsked(argc, argv, kUsage)) return 0;
  synthetic::SceneType scene = synthetic::SceneType::kCity;
  int frames = 10000, report_every = 1000;
  std::uint64_t seed = 1;
  bool parallel = false;
  std::string scene_text, frames_text, seed_text, every_text;
  std::string error = parseFlags(argc, argv,
                                 {{"--scene", &scene_text}, {"--frames", &frames_text}, {"--seed", &seed_text},
                                  {"--report-every", &every_text}},
                                 {{"--parallel", &parallel}});
  if (error.empty() && !scene_text.empty() && !synthetic::parseSceneType(scene_text, &scene)) error = "--scene takes city, village or highway";
  if (error.empty()) error = parseNumber("--frames", frames_text, &frames);
  if (error.empty()) error = parseNumber("--seed", seed_text, &seed);
  if (error.empty()) error = parseNumber("--report-every", every_text, &report_every);
  if (error.empty() && (frames < 1 || report_every < 1)) error = "--frames and --report-every take positive counts";
  if (!error.empty()) {
    std::cerr << "benchmark_memory: " << error << "\n" << kUsage;
    return 2;
  }
  synthetic::SyntheticSequence sequence(synthetic::SyntheticSequenceOptions::forScene(scene, seed));
  const FrameBuilder builder(FrameBuilderOptions{}, sequence.camera(), ClassTable::cityscapes().names());
  Odometry odometry(OdometryOptions{}, sequence.camera(), parallel ? MappingMode::kParallel : MappingMode::kDeterministic);
  std::printf("benchmark_memory: %s drive, seed %llu, %d frames, mapping %s\n", synthetic::toString(scene),
              static_cast<unsigned long long>(seed), frames, parallel ? "parallel" : "deterministic");
  double at_1000 = -1.0;
  int trusted = 0, keyframes = 0;
  for (int i = 0; i < frames; ++i) {
    const synthetic::SyntheticFrame frame = sequence.frame(i);
    ExtractionError extraction;
    const auto odometry_frame = builder.build(i, frame.time, frame.gray, ClassEvidence{}, &extraction);
    if (!odometry_frame) {
      std::fprintf(stderr, "benchmark_memory: frame %d: %s: %s\n", i, extraction.reason.c_str(), extraction.detail.c_str());
      return 1;
    }
    for (const FramePose& pose : odometry.process(odometry_frame)) trusted += pose.trusted;
    keyframes += static_cast<int>(odometry.takeNewWindows().size());
    if (i + 1 == 1000) at_1000 = residentMiB();
    if ((i + 1) % report_every == 0 || i + 1 == frames)
      std::printf("benchmark_memory: frame %d: resident %.1f MiB; %d trusted poses, %d keyframes so far\n", i + 1, residentMiB(),
                  trusted, keyframes);
    std::fflush(stdout);
  }
  odometry.finishMapping();
  const double at_end = residentMiB();
  if (at_1000 > 0.0 && at_end > 0.0)
    std::printf("benchmark_memory: resident at frame %d / at frame 1000: %.1f / %.1f MiB = %.3f\n", frames, at_end, at_1000,
                at_end / at_1000);
  std::printf("benchmark_memory: at frame %d once the allocator gave back its free pages: %.1f MiB\n", frames, trimmedResidentMiB());
  return 0;
}
