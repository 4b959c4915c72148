// The paper's convergence-basin experiment (IV-B2) on synthetic frame pairs with exact depth:
// the initial pose of the edge-only registration is displaced by 0 to 5 m in random directions
// (second table: rotated about random axes) and the registration runs with ANNF, ONNF and SNNF on
// the same edges, one pyramid level, the same Huber kernel.
//   convergence_benchmark --output DIR [--scene city|village|highway] [--pairs P] [--trials N]
//       [--seed S] [--reference-edges N] [--truncation PX] [--label-confusion X] [--edge-blur X]
//       [--missed-edges X] [--spurious-edges X]
// Prints the tables; writes DIR/convergence.json and the plots DIR/convergence.png (translation)
// and DIR/convergence_rotation.png.
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "semantic_edge_vo/common/class_table.h"
#include "semantic_edge_vo/support/command_line.h"
#include "semantic_edge_vo/experiments/convergence_experiment.h"
#include "semantic_edge_vo/eval/line_plot.h"
#include "semantic_edge_vo/frontend/point_sampler.h"
#include "semantic_edge_vo/synthetic/synthetic_sequence.h"

using namespace semantic_edge_vo;

namespace {

struct Arguments {
  std::string output;
  synthetic::SceneType scene = synthetic::SceneType::kCity;
  int pairs = 3, trials = 20, reference_edges = 3000;
  std::uint64_t seed = 1;
  float truncation = 150.0f;
  synthetic::NetworkNoiseOptions noise;
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
      if (!synthetic::parseSceneType(value, &args->scene)) *error = "--scene must be city, village or highway (got '" + value + "')";
    } else if (flag == "--pairs") *error = parseNumber(flag, value, &args->pairs);
    else if (flag == "--trials") *error = parseNumber(flag, value, &args->trials);
    else if (flag == "--seed") *error = parseNumber(flag, value, &args->seed);
    else if (flag == "--reference-edges") *error = parseNumber(flag, value, &args->reference_edges);
    else if (flag == "--truncation") {
      double truncation = args->truncation;
      *error = parseNumber(flag, value, &truncation);
      args->truncation = static_cast<float>(truncation);
    } else if (!synthetic::parseNoiseFlag(flag, value, &args->noise, error)) *error = "unknown flag " + flag;
    if (!error->empty()) return false;
  }
  if (args->output.empty()) *error = "--output DIR is required";
  else if (args->pairs < 1 || args->trials < 1 || args->reference_edges < 10) *error = "need --pairs >= 1, --trials >= 1, --reference-edges >= 10";
  return error->empty();
}

/// The simulated network's edge pixels: strength at least one half, direction from the image
/// gradient, classes from the network's labels. Dynamic (moving) pixels are left out when asked.
EdgeSet networkEdges(const synthetic::SyntheticFrame& frame, bool skip_dynamic) {
  cv::Mat smoothed, gx, gy;
  cv::GaussianBlur(frame.gray, smoothed, cv::Size(0, 0), 1.0);
  cv::Sobel(smoothed, gx, CV_32F, 1, 0, 3);
  cv::Sobel(smoothed, gy, CV_32F, 0, 1, 3);
  EdgeSet edges;
  for (int y = 2; y < frame.gray.rows - 2; ++y)
    for (int x = 2; x < frame.gray.cols - 2; ++x) {
      const std::uint8_t strength = frame.semantics.edge_strength.at<std::uint8_t>(y, x);
      const auto mask = static_cast<std::uint32_t>(frame.semantics.edge_classes.at<std::int32_t>(y, x));
      if (strength < 128 || !mask || (skip_dynamic && frame.dynamic.at<std::uint8_t>(y, x))) continue;
      const float dx = gx.at<float>(y, x), dy = gy.at<float>(y, x), magnitude = std::hypot(dx, dy);
      if (magnitude < 8.0f) continue;  // no reliable direction
      edges.push_back(static_cast<float>(x), static_cast<float>(y), dx / magnitude, dy / magnitude, strength / 255.0f, mask);
    }
  return edges;
}

RegistrationProblem makeProblem(synthetic::SyntheticSequence* sequence, int reference_index, int reference_edges) {
  const synthetic::SyntheticFrame reference = sequence->frame(reference_index);
  const synthetic::SyntheticFrame target = sequence->frame(reference_index + 1);
  RegistrationProblem problem;
  problem.camera = sequence->camera();
  problem.class_names = ClassTable::cityscapes().names();
  problem.T_target_ref = target.T_world_cam.inverse() * reference.T_world_cam;
  problem.target_edges = networkEdges(target, false);

  const EdgeSet candidates = networkEdges(reference, true);
  PointSamplerOptions sampling;
  sampling.max_edge_points = reference_edges;
  sampling.min_support_points = 0;
  for (std::uint32_t i : PointSampler(sampling).sample(reference.gray, candidates.view()).edge_indices) {
    const float depth = reference.depth.at<float>(static_cast<int>(candidates.v[i]), static_cast<int>(candidates.u[i]));
    if (!(depth > 0.5f)) continue;  // sky or too close
    problem.reference.push_back({problem.camera.backProject(candidates.u[i], candidates.v[i], depth),
                                 Eigen::Vector2d(candidates.normal_x[i], candidates.normal_y[i]), candidates.class_mask[i], 1.0});
  }
  return problem;
}

void printTable(const char* title, const char* unit, const std::vector<ConvergenceCurve>& curves, bool rotation) {
  std::printf("\n%s\n%10s", title, unit);
  for (const auto& c : curves) std::printf(" | %-5s success  median err", toString(c.kind));
  std::printf("\n");
  const std::size_t rows = rotation ? curves[0].rotation.size() : curves[0].translation.size();
  for (std::size_t r = 0; r < rows; ++r) {
    std::printf("%10.2f", (rotation ? curves[0].rotation : curves[0].translation)[r].displacement);
    for (const auto& c : curves) {
      const ConvergenceRow& row = (rotation ? c.rotation : c.translation)[r];
      std::printf(" | %11.0f%% %6.3f m %5.2f°", 100.0 * row.success_rate, row.median_error_m, row.median_error_deg);
    }
    std::printf("\n");
  }
  std::printf("%10s", "basin");
  for (const auto& c : curves) std::printf(" | %27.2f %s", rotation ? c.basin_deg : c.basin_m, rotation ? "deg" : "m  ");
  std::printf("\n");
}

void writePlot(const std::string& path, const std::vector<ConvergenceCurve>& curves, bool rotation, const std::string& title) {
  const std::map<FieldKind, std::array<int, 3>> colours = {
      {FieldKind::kAnnf, {{180, 120, 30}}}, {FieldKind::kOnnf, {{40, 160, 40}}}, {FieldKind::kSnnf, {{30, 30, 220}}}};
  std::vector<PlotSeries> series;
  for (const auto& c : curves) {
    PlotSeries s;
    s.label = std::string(toString(c.kind)) + " (basin " + tickLabel(rotation ? c.basin_deg : c.basin_m, 0.01) + ")";
    s.bgr = colours.at(c.kind);
    for (const auto& row : rotation ? c.rotation : c.translation) {
      s.x.push_back(row.displacement);
      s.y.push_back(100.0 * row.success_rate);
    }
    series.push_back(s);
  }
  LinePlotOptions options;
  options.title = title;
  options.x_label = rotation ? "initial rotation error (deg)" : "initial displacement (m)";
  options.y_label = "success rate (%)";
  cv::imwrite(path, renderLinePlot(series, options));
}

}  // namespace

const char* const kUsage =
    "usage: convergence_benchmark --output DIR [--scene city|village|highway] [--pairs P] [--trials N]\n"
    "         [--seed S] [--reference-edges N] [--truncation PX] [--label-confusion X] [--edge-blur X]\n"
    "         [--missed-edges X] [--spurious-edges X]\n"
    "         (defaults: city, 3 pairs, 20 trials, seed 1, 3000 reference edges, truncation 150 px,\n"
    "         no network noise)\n";

int main(int argc, char** argv) {
  if (printUsageIfAsked(argc, argv, kUsage)) return 0;
  Arguments args;
  std::string error;
  if (!parse(argc, argv, &args, &error)) {
    std::fprintf(stderr, "convergence_benchmark: %s\n%s", error.c_str(), kUsage);
    return 2;
  }
  synthetic::SyntheticSequenceOptions sequence_options = synthetic::SyntheticSequenceOptions::forScene(args.scene, args.seed);
  sequence_options.network_noise = args.noise;
  ConvergenceOptions options;
  options.trials = args.trials;
  options.seed = args.seed;
  options.field.truncation_radius = args.truncation;
  options.registration.max_iterations = 30;
  error = sequence_options.validate();
  if (error.empty()) error = options.validate();
  if (!error.empty()) {
    std::fprintf(stderr, "convergence_benchmark: %s\n", error.c_str());
    return 2;
  }
  std::filesystem::create_directories(args.output);

  synthetic::SyntheticSequence sequence(sequence_options);
  std::vector<RegistrationProblem> problems;
  for (int p = 0; p < args.pairs; ++p) {
    problems.push_back(makeProblem(&sequence, 5 + 10 * p, args.reference_edges));
    std::fprintf(stderr, "pair %d: frames %d-%d, %zu reference edges, %zu target edges, %.2f m apart\n", p, 5 + 10 * p,
                 6 + 10 * p, problems.back().reference.size(), problems.back().target_edges.size(),
                 problems.back().T_target_ref.translation().norm());
  }
  std::vector<ConvergenceCurve> curves;
  for (FieldKind kind : {FieldKind::kAnnf, FieldKind::kOnnf, FieldKind::kSnnf}) {
    std::fprintf(stderr, "registering with %s ...\n", toString(kind));
    curves.push_back(runConvergence(problems, kind, options));
  }
  std::ostringstream description;
  description << "scene " << synthetic::toString(args.scene) << ", seed " << args.seed << ", " << args.pairs << " frame pairs, "
              << args.trials << " trials per displacement and pair, single level, Huber " << options.registration.huber_threshold
              << " px, truncation " << args.truncation << " px, success below " << options.success_translation_m << " m and "
              << options.success_rotation_deg << " deg; network noise: label confusion " << args.noise.label_confusion
              << ", edge blur " << args.noise.edge_blur << ", missed " << args.noise.missed_edges << ", spurious "
              << args.noise.spurious_edges;
  std::printf("convergence basins: %s\n", description.str().c_str());
  printTable("initial pose displaced in random 3D directions", "metres", curves, false);
  printTable("initial pose rotated about random axes", "degrees", curves, true);

  const std::string json_path = args.output + "/convergence.json";
  std::ofstream(json_path) << convergenceJson(curves, description.str());
  writePlot(args.output + "/convergence.png", curves, false,
            std::string("Convergence basin, ") + synthetic::toString(args.scene) + ": initial displacement");
  writePlot(args.output + "/convergence_rotation.png", curves, true,
            std::string("Convergence basin, ") + synthetic::toString(args.scene) + ": initial rotation");
  std::printf("\nwrote %s, %s/convergence.png, %s/convergence_rotation.png\n", json_path.c_str(), args.output.c_str(),
              args.output.c_str());
  return 0;
}
