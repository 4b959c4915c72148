// Renders a synthetic driving sequence with exact ground truth into a KITTI-odometry-style folder
// (and optionally a rosbag). Formats: docs/synthetic_sequences.md.
//   make_synthetic_sequence --scene city|village|highway --frames N --seed S --output DIR [--bag FILE]
//       [--label-confusion X] [--edge-blur X] [--missed-edges X] [--spurious-edges X]   (0..1)
//       [--stop-at M] [--stop-for S] [--vibration DEG] [--no-semantics] [--no-traffic] [--quiet]
// Rendering and file writing run on two threads; a progress bar goes to stderr.
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <deque>
#include <iostream>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

#include "semantic_edge_vo/support/command_line.h"
#include "semantic_edge_vo/support/progress_bar.h"
#include "semantic_edge_vo/ros/bags/sequence_bag_writer.h"
#include "semantic_edge_vo/synthetic/sequence_directory_writer.h"
#include "semantic_edge_vo/synthetic/synthetic_sequence.h"

namespace {

using semantic_edge_vo::ProgressBar;
using semantic_edge_vo::parseFlags;
using semantic_edge_vo::parseNumber;
using semantic_edge_vo::SequenceBagWriter;
using namespace semantic_edge_vo::synthetic;

const char* const kUsage =
    "usage: make_synthetic_sequence --scene city|village|highway --frames N --seed S --output DIR [--bag FILE]\n"
    "         [--label-confusion X] [--edge-blur X] [--missed-edges X] [--spurious-edges X]  (strengths 0..1)\n"
    "         [--stop-at M] [--stop-for S]  (a stop M metres along the route, standing S s, default 5)\n"
    "         [--vibration DEG]  (pitch and roll jitter amplitude; default the scene's: 0.086, highway 0.057)\n"
    "         [--no-semantics] [--no-traffic] [--quiet]\n";

struct Arguments {
  SceneType scene = SceneType::kCity;
  int frames = 0;
  std::uint64_t seed = 1;
  std::string output, bag;
  NetworkNoiseOptions noise;
  double stop_at = -1.0, stop_duration = 5.0;  ///< m, s (EgoMotionOptions)
  double vibration_deg = -1.0;                 ///< < 0: the scene's
  bool semantics = true, traffic = true, quiet = false;
};

bool parse(int argc, char** argv, Arguments* args, std::string* error) {
  std::string scene, frames, seed, stop_at, stop_duration, vibration;
  std::map<std::string, std::string> noise;
  for (const std::string& flag : noiseFlags()) noise[flag] = "";
  std::map<std::string, std::string*> values = {{"--scene", &scene}, {"--frames", &frames}, {"--seed", &seed}, {"--output", &args->output},
                                                {"--bag", &args->bag}, {"--stop-at", &stop_at}, {"--stop-for", &stop_duration},
                                                {"--vibration", &vibration}};
  for (auto& [flag, text] : noise) values[flag] = &text;
  bool no_semantics = false, no_traffic = false;
  *error = parseFlags(argc, argv, values, {{"--no-semantics", &no_semantics}, {"--no-traffic", &no_traffic}, {"--quiet", &args->quiet}});
  args->semantics = !no_semantics;
  args->traffic = !no_traffic;
  if (error->empty() && !scene.empty() && !parseSceneType(scene, &args->scene)) *error = "--scene takes city, village or highway";
  if (error->empty()) *error = parseNumber("--frames", frames, &args->frames);
  if (error->empty()) *error = parseNumber("--seed", seed, &args->seed);
  if (error->empty()) *error = parseNumber("--stop-at", stop_at, &args->stop_at);
  if (error->empty()) *error = parseNumber("--stop-for", stop_duration, &args->stop_duration);
  if (error->empty()) *error = parseNumber("--vibration", vibration, &args->vibration_deg);
  if (error->empty() && !stop_at.empty() && args->stop_at < 0.0) *error = "--stop-at takes a distance >= 0, m";
  if (error->empty() && !vibration.empty() && !(args->vibration_deg >= 0.0 && args->vibration_deg <= 10.0))
    *error = "--vibration takes an amplitude in [0, 10] deg";
  for (const auto& [flag, text] : noise)
    if (error->empty() && !text.empty()) parseNoiseFlag(flag, text, &args->noise, error);
  if (!error->empty()) return false;
  if (frames.empty()) *error = "--frames is required";
  else if (args->frames < 1 || args->frames > 10000000) *error = "--frames takes a positive count";
  else if (args->output.empty()) *error = "--output is required";
  return error->empty();
}

/// Frames rendered but not yet written, bounded so memory stays small.
class FrameQueue {
 public:
  void push(std::unique_ptr<SyntheticFrame> frame) {
    std::unique_lock<std::mutex> lock(mutex_);
    changed_.wait(lock, [&] { return frames_.size() < 3; });
    frames_.push_back(std::move(frame));
    changed_.notify_all();
  }
  /// Null after close() once empty.
  std::unique_ptr<SyntheticFrame> pop() {
    std::unique_lock<std::mutex> lock(mutex_);
    changed_.wait(lock, [&] { return !frames_.empty() || closed_; });
    if (frames_.empty()) return nullptr;
    auto frame = std::move(frames_.front());
    frames_.pop_front();
    changed_.notify_all();
    return frame;
  }
  void close() {
    std::lock_guard<std::mutex> lock(mutex_);
    closed_ = true;
    changed_.notify_all();
  }

 private:
  std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<std::unique_ptr<SyntheticFrame>> frames_;
  bool closed_ = false;
};

}  // namespace

int main(int argc, char** argv) {
  if (semantic_edge_vo::printUsageIfAsked(argc, argv, kUsage)) return 0;
  Arguments args;
  std::string error;
  if (!parse(argc, argv, &args, &error)) {
    std::cerr << "make_synthetic_sequence: " << error << "\n" << kUsage;
    return 2;
  }
  SyntheticSequenceOptions options = SyntheticSequenceOptions::forScene(args.scene, args.seed);
  options.network_noise = args.noise;
  options.semantics = args.semantics;
  options.world.traffic = args.traffic;
  options.world.ego.stop_at = args.stop_at;
  options.world.ego.stop_duration = args.stop_duration;
  if (args.vibration_deg >= 0.0) options.world.ego.vibration = args.vibration_deg * M_PI / 180.0;
  if (const std::string invalid = options.validate(); !invalid.empty()) {
    std::cerr << "make_synthetic_sequence: " << invalid << "\n";
    return 2;
  }
  SequenceDirectoryWriter directory(args.output, options, args.frames);
  if (!directory.error().empty()) {
    std::cerr << "make_synthetic_sequence: " << directory.error() << "\n";
    return 1;
  }
  std::unique_ptr<SequenceBagWriter> bag;
  if (!args.bag.empty()) {
    bag = std::make_unique<SequenceBagWriter>(args.bag, options.camera, options.semantics);
    if (!bag->error().empty()) {
      std::cerr << "make_synthetic_sequence: " << bag->error() << "\n";
      return 1;
    }
  }

  const auto start = std::chrono::steady_clock::now();
  SyntheticSequence sequence(options);
  FrameQueue queue;
  ProgressBar progress(args.frames, !args.quiet);
  std::string write_error;
  const semantic_edge_vo::ClassTable classes = semantic_edge_vo::ClassTable::cityscapes();
  std::thread writer([&] {
    int written = 0;
    while (auto frame = queue.pop()) {
      if (!write_error.empty()) continue;  // drain
      const EncodedFrame files = encodeFrame(*frame, options.semantics, classes);
      if (!directory.write(*frame, files)) write_error = directory.error();
      else if (bag && !bag->write(*frame, files)) write_error = bag->error();
      progress.update(++written);
    }
  });
  for (int i = 0; i < args.frames; ++i) queue.push(std::make_unique<SyntheticFrame>(sequence.frame(i)));
  queue.close();
  writer.join();
  if (bag) bag->close();
  if (!write_error.empty()) {
    std::cerr << "make_synthetic_sequence: " << write_error << "\n";
    return 1;
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!args.quiet)
    std::cerr << "wrote " << args.frames << " " << toString(args.scene) << " frames to " << args.output
              << (bag ? " and " + args.bag : std::string()) << " in " << seconds << " s ("
              << args.frames / seconds << " frames/s)\n";
  return 0;
}
