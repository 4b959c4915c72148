// Speed of the synthetic sequence generator on one core: renders frames (all channels) and encodes
// them as the sequence writer does (PNG, in memory), and prints frames per second of each.
//   benchmark_synthetic [--scene city|village|highway] [--frames N] [--seed S] [--no-semantics]
#include <chrono>
#include <cstdio>
#include <iostream>
#include <string>
#include <vector>

#include <opencv2/core/utility.hpp>
#include <opencv2/imgcodecs.hpp>

#include "semantic_edge_vo/class_table.h"
#include "semantic_edge_vo/synthetic/sequence_formats.h"
#include "semantic_edge_vo/synthetic/synthetic_sequence.h"

using namespace semantic_edge_vo::synthetic;

namespace {

double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

std::size_t encodedSize(const cv::Mat& image) {
  std::vector<std::uint8_t> buffer;
  cv::imencode(".png", image, buffer, {cv::IMWRITE_PNG_COMPRESSION, 1});
  return buffer.size();
}

}  // namespace

int main(int argc, char** argv) {
  SceneType scene = SceneType::kCity;
  int frames = 50;
  std::uint64_t seed = 1;
  bool semantics = true;
  for (int i = 1; i < argc; ++i) {
    const std::string flag = argv[i];
    const bool has_value = i + 1 < argc;
    if (flag == "--scene" && has_value && parseSceneType(argv[i + 1], &scene)) ++i;
    else if (flag == "--frames" && has_value) frames = std::max(1, std::atoi(argv[++i]));
    else if (flag == "--seed" && has_value) seed = std::strtoull(argv[++i], nullptr, 10);
    else if (flag == "--no-semantics") semantics = false;
    else {
      std::cerr << "usage: benchmark_synthetic [--scene city|village|highway] [--frames N] [--seed S] [--no-semantics]\n";
      return 2;
    }
  }
  cv::setNumThreads(1);  // one core, as the requirement states it
  SyntheticSequenceOptions options = SyntheticSequenceOptions::forScene(scene, seed);
  options.semantics = semantics;
  SyntheticSequence sequence(options);
  const semantic_edge_vo::ClassTable classes = semantic_edge_vo::ClassTable::cityscapes();

  double render_seconds = 0.0, encode_seconds = 0.0;
  std::size_t bytes = 0;
  for (int i = 0; i < frames; ++i) {
    auto start = std::chrono::steady_clock::now();
    const SyntheticFrame frame = sequence.frame(i);
    render_seconds += secondsSince(start);
    start = std::chrono::steady_clock::now();
    bytes += encodedSize(frame.gray) + encodedSize(frame.color) + encodedSize(encodeDepth(frame.depth)) +
             encodedSize(frame.class_id) + encodedSize(colorizeClasses(frame.class_id, classes)) + encodedSize(frame.dynamic);
    if (semantics)
      bytes += encodedSize(frame.semantics.edge_strength) + encodedSize(maskBytes(frame.semantics.edge_classes)) +
               encodedSize(frame.semantics.class_probability);
    encode_seconds += secondsSince(start);
  }
  const double mb_per_frame = bytes / 1e6 / frames;
  std::printf("scene %s, %d frames of %dx%d, one thread\n", toString(scene), frames, options.camera.width,
              options.camera.height);
  std::printf("render (all channels): %6.1f frames/s  (%.1f ms/frame)\n", frames / render_seconds,
              1e3 * render_seconds / frames);
  std::printf("PNG encoding:          %6.1f frames/s  (%.1f ms/frame)\n", frames / encode_seconds,
              1e3 * encode_seconds / frames);
  std::printf("render + encoding:     %6.1f frames/s\n", frames / (render_seconds + encode_seconds));
  std::printf("files: %.2f MB/frame, %.2f GB per 1000 frames\n", mb_per_frame, mb_per_frame);
  return 0;
}
