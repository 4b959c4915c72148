// Prints how long building nearest-neighbour fields takes and how much memory they hold, for
// ANNF, ONNF and SNNF over all pyramid levels of one frame (median of repeated runs, one core).
//   benchmark_fields [--image PNG] [--classes N] [--levels L] [--runs R] [--cell PX]
// Default image: KITTI 06 frame 0 from ../shared when present, else the generated test pattern at
// 1241x376. Edges: Canny; classes: a spatial layout of N classes (region of 48x48 px), edge pixels
// on a region border get both classes, like semantic boundary edges.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include <opencv2/imgcodecs.hpp>

#include "semantic_edge_vo/edges/canny_edge_detector.h"
#include "semantic_edge_vo/support/command_line.h"
#include "semantic_edge_vo/fields/nearest_neighbor_field.h"
#include "semantic_edge_vo/support/test_pattern.h"

using namespace semantic_edge_vo;

namespace {

std::size_t bytesOf(const NearestNeighborFieldData& field) {
  std::size_t bytes = 0;
  for (const auto& l : field.levels)
    bytes += 4 * (l.seed_u.size() * 5 + l.cell_start.size() + l.entry_seed.size());
  return bytes;
}

std::uint32_t regionClass(float u, float v, int classes) {
  const int rx = static_cast<int>(u) / 48, ry = static_cast<int>(v) / 48;
  return static_cast<std::uint32_t>((rx * 7 + ry * 13) % classes);
}

}  // namespace

const char* const kUsage =
    "usage: benchmark_fields [--image PNG] [--classes N] [--levels L] [--runs R] [--cell PX]\n"
    "  default image: KITTI 06 frame 0 from ../shared (else a generated test pattern at 1241x376);\n"
    "  --classes 19, --levels 4, --runs 50, --cell: the field's bucket side at level 0 (4)\n";

int main(int argc, char** argv) {
  if (printUsageIfAsked(argc, argv, kUsage)) return 0;
  std::string image_path = std::string(SEVO_DEFAULT_SHARED_DIR) + "/data/kitti_odometry/sequences/06/image_0/000000.png";
  int classes = 19, levels = 4, runs = 50, cell_size = FieldOptions().cell_size;
  std::string classes_text, levels_text, runs_text, cell_text;
  std::string error = parseFlags(argc, argv,
                                 {{"--image", &image_path}, {"--classes", &classes_text}, {"--levels", &levels_text},
                                  {"--runs", &runs_text}, {"--cell", &cell_text}},
                                 {});
  if (error.empty()) error = parseNumber("--classes", classes_text, &classes);
  if (error.empty()) error = parseNumber("--levels", levels_text, &levels);
  if (error.empty()) error = parseNumber("--runs", runs_text, &runs);
  if (error.empty()) error = parseNumber("--cell", cell_text, &cell_size);
  if (!error.empty()) {
    std::fprintf(stderr, "benchmark_fields: %s\n%s", error.c_str(), kUsage);
    return 2;
  }
  if (classes < 1 || classes > 32 || levels < 1 || runs < 1) {
    std::fprintf(stderr, "benchmark_fields: need 1 <= classes <= 32, levels >= 1, runs >= 1\n");
    return 2;
  }
  cv::Mat gray = cv::imread(image_path, cv::IMREAD_GRAYSCALE);
  if (gray.empty()) {
    std::printf("(no image at %s: using the generated test pattern at 1241x376)\n", image_path.c_str());
    gray = renderTestPattern(0, 1241, 376);
  }
  EdgeSet edges = CannyEdgeDetector(CannyOptions()).detect(gray);
  for (std::size_t i = 0; i < edges.size(); ++i) {
    const float nx = edges.normal_x[i] * 2.0f, ny = edges.normal_y[i] * 2.0f;
    edges.class_mask[i] = (1u << regionClass(edges.u[i] - nx, edges.v[i] - ny, classes)) |
                          (1u << regionClass(edges.u[i] + nx, edges.v[i] + ny, classes));
  }
  std::vector<std::string> names(static_cast<std::size_t>(classes), "class");
  std::printf("image %dx%d, %zu edge pixels, %d classes, %d levels, median of %d runs\n", gray.cols, gray.rows,
              edges.size(), classes, levels, runs);
  // Queries as tracking makes them: near edges (3 px jitter), in a layer the edge seeds.
  std::mt19937 rng(1);
  std::normal_distribution<float> jitter(0.0f, 3.0f);
  std::uniform_int_distribution<std::size_t> pick(0, edges.size() - 1);
  std::vector<std::size_t> query_edges(100000);
  std::vector<float> query_du(query_edges.size()), query_dv(query_edges.size());
  for (std::size_t q = 0; q < query_edges.size(); ++q) {
    query_edges[q] = pick(rng);
    query_du[q] = jitter(rng);
    query_dv[q] = jitter(rng);
  }
  std::printf("%-6s %8s %10s %12s %16s\n", "field", "layers", "build ms", "memory MB", "lookup ns (L0)");
  for (FieldKind kind : {FieldKind::kAnnf, FieldKind::kOnnf, FieldKind::kSnnf}) {
    FieldOptions options;
    options.kind = kind;
    options.pyramid_levels = levels;
    options.cell_size = cell_size;
    std::vector<double> times;
    NearestNeighborFieldData field;
    for (int r = 0; r < runs; ++r) {
      const auto start = std::chrono::steady_clock::now();
      field = buildNearestNeighborField(edges.view(), gray.cols, gray.rows, names, options);
      times.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
    }
    std::nth_element(times.begin(), times.begin() + runs / 2, times.end());
    const NearestNeighborFieldView view = field.view();
    FieldMatch match;
    int hits = 0;
    const auto start = std::chrono::steady_clock::now();
    for (std::size_t q = 0; q < query_edges.size(); ++q) {
      const std::size_t e = query_edges[q];
      const int layer = kind == FieldKind::kAnnf   ? 0
                        : kind == FieldKind::kOnnf ? view.orientationBin(edges.normal_x[e], edges.normal_y[e])
                                                   : __builtin_ctz(edges.class_mask[e]);
      hits += view.nearest(0, layer, edges.u[e] + query_du[q], edges.v[e] + query_dv[q], &match);
    }
    const double lookup_ns =
        std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - start).count() / query_edges.size();
    std::printf("%-6s %8d %10.2f %12.2f %16.1f   (%d%% found)\n", toString(kind), field.num_layers,
                times[static_cast<std::size_t>(runs / 2)], bytesOf(field) / 1e6, lookup_ns,
                static_cast<int>(100.0 * hits / query_edges.size()));
  }
  return 0;
}
