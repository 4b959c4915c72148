// The paper's edge repeatability experiment (IV-B1) on synthetic sequences with exact depth and
// poses: for frame pairs (i, i + g), g = 1..K, a fixed random sample of frame i's edge pixels per
// detector (with depth, static, visible in frame i + g) is projected into frame i + g, and a pixel
// counts as re-detected when the same detector has an edge there within the radius (semantic
// detectors: also an edge of a shared class). Detectors: canny (gray image), fused (Canny x the
// simulated network's class labels), semantic_edges (the network's per-class edges, bitmask form),
// and fused / semantic_edges on the network output with the noise models applied.
//   edge_repeatability --output DIR [--scene city|village|highway|all] [--pairs N] [--sample N]
//       [--frame-gap K] [--radius PX] [--seed S] [--label-confusion X] [--edge-blur X]
//       [--missed-edges X] [--spurious-edges X]
// Noise strengths default to 0.3 each; all 0 leaves the noisy detectors out. Prints a table per
// scene; writes DIR/repeatability.json and DIR/repeatability.png (same-class repeatability over the
// frame gap, one panel per scene; Canny's single class makes it its plain repeatability).
#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "semantic_edge_vo/common/class_table.h"
#include "semantic_edge_vo/support/command_line.h"
#include "semantic_edge_vo/experiments/edge_repeatability.h"
#include "semantic_edge_vo/eval/line_plot.h"
#include "semantic_edge_vo/edges/semantic_edge_extractor.h"
#include "semantic_edge_vo/synthetic/random.h"
#include "semantic_edge_vo/synthetic/sequence_formats.h"
#include "semantic_edge_vo/synthetic/synthetic_sequence.h"

using namespace semantic_edge_vo;

namespace {

struct Arguments {
  std::string output;
  std::vector<synthetic::SceneType> scenes = {synthetic::SceneType::kCity};
  int pairs = 5, frame_gap = 3;
  RepeatabilityOptions repeatability;
  synthetic::NetworkNoiseOptions noise{0.3, 0.3, 0.3, 0.3};
};

bool parse(int argc, char** argv, Arguments* args, std::string* error) {
  for (int i = 1; i < argc; ++i) {
    const std::string flag = argv[i];
    if (i + 1 >= argc) {
      *error = flag + " needs a value";
      return false;
    }
    const std::string value = argv[++i];
    if (value.empty()) *error = flag + " needs a value";  // parseNumber would keep the default
    else if (flag == "--output") args->output = value;
    else if (flag == "--scene") {
      synthetic::SceneType scene;
      if (value == "all") args->scenes = {synthetic::SceneType::kCity, synthetic::SceneType::kVillage, synthetic::SceneType::kHighway};
      else if (synthetic::parseSceneType(value, &scene)) args->scenes = {scene};
      else *error = "--scene must be city, village, highway or all (got '" + value + "')";
    } else if (flag == "--pairs") *error = parseNumber(flag, value, &args->pairs);
    else if (flag == "--sample") *error = parseNumber(flag, value, &args->repeatability.sample_size);
    else if (flag == "--frame-gap") *error = parseNumber(flag, value, &args->frame_gap);
    else if (flag == "--radius") *error = parseNumber(flag, value, &args->repeatability.radius);
    else if (flag == "--seed") *error = parseNumber(flag, value, &args->repeatability.seed);
    else if (!synthetic::parseNoiseFlag(flag, value, &args->noise, error)) *error = "unknown flag " + flag;
    if (!error->empty()) return false;
  }
  if (args->output.empty()) *error = "--output DIR is required";
  else if (args->pairs < 1 || args->frame_gap < 1 || args->frame_gap > 20) *error = "need --pairs >= 1 and --frame-gap in [1, 20]";
  else if (!(*error = args->repeatability.validate()).empty()) return false;
  else *error = args->noise.validate();
  return error->empty();
}

/// One detector: its name, whether its classes mean anything, and its edges of a frame.
struct Detector {
  std::string name;
  bool semantic = false;
  bool noisy = false;  ///< sees the network output with the noise models applied
  std::array<int, 3> bgr;
  std::function<EdgeSet(const synthetic::SyntheticFrame&, const synthetic::SemanticNetworkOutput&)> detect;
};

EdgeSet extract(IntakeMode mode, const cv::Mat& gray, const ClassEvidence& classes) {
  SemanticEdgeOptions options;
  options.mode = mode;
  EdgeSet edges;
  if (ExtractionError error = SemanticEdgeExtractor(options).extract(gray, classes, cv::Mat(), &edges))
    throw std::runtime_error(error.reason + ": " + error.detail);
  return edges;
}

std::vector<Detector> detectors(bool noisy) {
  const int classes = ClassTable::cityscapes().size();
  auto fused = [classes](const synthetic::SyntheticFrame& frame, const synthetic::SemanticNetworkOutput& semantics) {
    return extract(IntakeMode::kFused, frame.gray, {ClassEvidenceForm::kLabels, synthetic::classLabels(semantics), classes});
  };
  auto semantic = [classes](const synthetic::SyntheticFrame& frame, const synthetic::SemanticNetworkOutput& semantics) {
    return extract(IntakeMode::kSemanticEdges, frame.gray,
                   {ClassEvidenceForm::kBitmask, synthetic::packEdgeBitmask(semantics), classes});
  };
  std::vector<Detector> out = {
      {"canny", false, false, {{180, 120, 30}},
       [](const synthetic::SyntheticFrame& frame, const synthetic::SemanticNetworkOutput&) {
         return extract(IntakeMode::kCanny, frame.gray, {});
       }},
      {"fused", true, false, {{40, 160, 40}}, fused},
      {"semantic_edges", true, false, {{30, 30, 220}}, semantic}};
  if (noisy) {
    out.push_back({"fused+noise", true, true, {{120, 200, 120}}, fused});
    out.push_back({"semantic+noise", true, true, {{160, 120, 240}}, semantic});
  }
  return out;
}

/// The edges of every detector in one frame (noisy detectors see the network output with noise).
std::vector<EdgeSet> detectAll(const std::vector<Detector>& list, const synthetic::SyntheticFrame& frame,
                               const synthetic::NetworkNoiseOptions& noise, std::uint64_t seed) {
  synthetic::SemanticNetworkOutput noisy = frame.semantics.clone();
  if (noise.any()) synthetic::applyNetworkNoise(noise, synthetic::hashCombine(seed, static_cast<std::uint64_t>(frame.index)), &noisy);
  std::vector<EdgeSet> edges;
  for (const Detector& d : list) edges.push_back(d.detect(frame, d.noisy ? noisy : frame.semantics));
  return edges;
}

RepeatabilityFrame groundTruth(const synthetic::SyntheticFrame& frame, const EdgeSet& edges) {
  RepeatabilityFrame out;
  out.edges = edges.view();
  out.depth = frame.depth;
  out.dynamic = frame.dynamic;
  out.T_world_cam = frame.T_world_cam;
  return out;
}

/// Results of one scene, indexed [detector][gap - 1].
std::vector<std::vector<RepeatabilityResult>> runScene(synthetic::SceneType scene, const Arguments& args,
                                                       const std::vector<Detector>& list) {
  synthetic::SyntheticSequenceOptions sequence_options = synthetic::SyntheticSequenceOptions::forScene(scene, args.repeatability.seed);
  synthetic::SyntheticSequence sequence(sequence_options);
  std::vector<std::vector<RepeatabilityResult>> results(list.size());
  for (std::size_t d = 0; d < list.size(); ++d)
    for (int gap = 1; gap <= args.frame_gap; ++gap)
      results[d].push_back({synthetic::toString(scene), list[d].name, gap, list[d].semantic, 0, {}});
  const int stride = std::max(10, args.frame_gap + 1);
  for (int p = 0; p < args.pairs; ++p) {
    std::vector<synthetic::SyntheticFrame> frames;
    std::vector<std::vector<EdgeSet>> edges;  // [frame][detector]
    for (int g = 0; g <= args.frame_gap; ++g) {
      frames.push_back(sequence.frame(5 + stride * p + g));
      edges.push_back(detectAll(list, frames.back(), args.noise, args.repeatability.seed));
    }
    std::fprintf(stderr, "%s: frames %d-%d\n", synthetic::toString(scene), frames.front().index, frames.back().index);
    for (std::size_t d = 0; d < list.size(); ++d)
      for (int gap = 1; gap <= args.frame_gap; ++gap) {
        RepeatabilityResult& result = results[d][static_cast<std::size_t>(gap - 1)];
        result.count += measureRepeatability(sequence.camera(), groundTruth(frames[0], edges[0][d]),
                                             groundTruth(frames[static_cast<std::size_t>(gap)], edges[static_cast<std::size_t>(gap)][d]),
                                             args.repeatability);
        ++result.pairs;
      }
  }
  return results;
}

void printTable(const std::string& scene, const std::vector<std::vector<RepeatabilityResult>>& results) {
  std::printf("\n%s (repeatability %% / same class %%, by frame gap)\n%-21s %10s %9s", scene.c_str(), "detector", "edges/frame",
              "sampled");
  for (const RepeatabilityResult& r : results[0]) std::printf(" |  gap %d        ", r.frame_gap);
  std::printf("\n");
  for (const auto& row : results) {
    std::printf("%-21s %10.0f %9.0f", row[0].detector.c_str(), static_cast<double>(row[0].count.edges) / row[0].pairs,
                static_cast<double>(row[0].count.sampled) / row[0].pairs);
    for (const RepeatabilityResult& r : row) {
      if (r.semantic) std::printf(" | %5.1f / %5.1f  ", 100.0 * r.count.rate(), 100.0 * r.count.classRate());
      else std::printf(" | %5.1f /   -    ", 100.0 * r.count.rate());
    }
    std::printf("\n");
  }
}

cv::Mat plotScene(const std::string& scene, const std::vector<std::vector<RepeatabilityResult>>& results,
                  const std::vector<Detector>& list, double radius) {
  std::vector<PlotSeries> series;
  for (std::size_t d = 0; d < list.size(); ++d) {
    PlotSeries s;
    s.label = list[d].name;
    s.bgr = list[d].bgr;
    for (const RepeatabilityResult& r : results[d]) {
      s.x.push_back(r.frame_gap);
      s.y.push_back(100.0 * r.count.classRate());  // canny: one class, so any edge
    }
    series.push_back(s);
  }
  LinePlotOptions options;
  options.width_px = 800;
  options.height_px = 500;
  options.y_from_zero = false;
  options.title = "Edge repeatability, " + scene + " (r = " + tickLabel(radius, 0.1) + " px)";
  options.x_label = "frame gap";
  options.y_label = "re-detected with a shared class (%)";
  return renderLinePlot(series, options);
}

}  // namespace

const char* const kUsage =
    "usage: edge_repeatability --output DIR [--scene city|village|highway|all] [--pairs N] [--sample N]\n"
    "         [--frame-gap K] [--radius PX] [--seed S] [--label-confusion X] [--edge-blur X]\n"
    "         [--missed-edges X] [--spurious-edges X]   (defaults: city, 5 pairs, 9000 pixels,\n"
    "         gaps 1..3, 1.5 px, seed 1, noise strengths 0.3; all 0 leaves the noisy detectors out)\n";

int main(int argc, char** argv) {
  if (printUsageIfAsked(argc, argv, kUsage)) return 0;
  Arguments args;
  std::string error;
  if (!parse(argc, argv, &args, &error)) {
    std::fprintf(stderr, "edge_repeatability: %s\n%s", error.c_str(), kUsage);
    return 2;
  }
  std::filesystem::create_directories(args.output);
  const std::vector<Detector> list = detectors(args.noise.any());
  std::vector<RepeatabilityResult> all;
  std::vector<cv::Mat> panels;
  try {
    for (synthetic::SceneType scene : args.scenes) {
      const auto results = runScene(scene, args, list);
      printTable(synthetic::toString(scene), results);
      panels.push_back(plotScene(synthetic::toString(scene), results, list, args.repeatability.radius));
      for (const auto& row : results) all.insert(all.end(), row.begin(), row.end());
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "edge_repeatability: %s\n", e.what());
    return 1;
  }
  std::ostringstream description;
  description << "seed " << args.repeatability.seed << ", " << args.pairs << " frame pairs per scene and gap, up to "
              << args.repeatability.sample_size << " sampled edge pixels per detector and pair, radius " << args.repeatability.radius
              << " px; noisy detectors: label confusion " << args.noise.label_confusion << ", edge blur " << args.noise.edge_blur
              << ", missed " << args.noise.missed_edges << ", spurious " << args.noise.spurious_edges;
  std::printf("\n%s\n", description.str().c_str());
  const std::string json_path = args.output + "/repeatability.json", png_path = args.output + "/repeatability.png";
  std::ofstream(json_path) << repeatabilityJson(all, args.repeatability, description.str());
  cv::Mat plot;
  cv::hconcat(panels, plot);
  cv::imwrite(png_path, plot);
  std::printf("wrote %s, %s\n", json_path.c_str(), png_path.c_str());
  return 0;
}
