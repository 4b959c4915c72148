// Prints the median time of the edge intake (edges, classes, point sample) of one 1241x376 frame
// with 19 classes per mode and class input form, on one core, and the segmenter's time per frame.
//   benchmark_intake [--image PNG] [--segmenter-model PATH] [--runs R] [--segmenter-runs S]
// Default image: KITTI 06 frame 0 from ../shared, resized to 1241x376 (the generated test pattern
// when absent). Class probabilities: ENet's on that frame when the model is found (default
// ../shared/models/enet_cityscapes), else synthetic blobs. Per-class edge probabilities for the
// semantic_edges rows are made from the class probabilities (gradient of each plane).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "semantic_edge_vo/common/robust_statistics.h"
#include "semantic_edge_vo/common/class_table.h"
#include "semantic_edge_vo/support/command_line.h"
#include "semantic_edge_vo/frontend/point_sampler.h"
#include "semantic_edge_vo/edges/class_map_carrier.h"
#include "semantic_edge_vo/edges/segmenter.h"
#include "semantic_edge_vo/sequences/semantic_map_files.h"
#include "semantic_edge_vo/edges/semantic_edge_extractor.h"
#include "semantic_edge_vo/support/test_pattern.h"

using namespace semantic_edge_vo;

namespace {

constexpr int kWidth = 1241, kHeight = 376;

double threadCpuMs() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return 1e3 * static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_nsec);
}


/// Median wall time of `work`, ms.
double medianMs(int runs, const std::function<void()>& work) {
  std::vector<double> ms;
  for (int i = 0; i < runs; ++i) {
    const auto start = std::chrono::steady_clock::now();
    work();
    ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
  }
  return median(ms);
}

/// Softmax of smooth random scores: blobs of classes, like a segmentation.
cv::Mat syntheticProbabilities(int classes) {
  std::mt19937 random(7);
  std::vector<cv::Mat> planes(static_cast<std::size_t>(classes));
  cv::Mat sum(kHeight, kWidth, CV_32F, cv::Scalar(0));
  for (auto& plane : planes) {
    cv::Mat coarse(kHeight / 32 + 1, kWidth / 32 + 1, CV_32F);
    cv::randn(coarse, 0.0, 3.0);
    cv::resize(coarse, plane, cv::Size(kWidth, kHeight), 0, 0, cv::INTER_CUBIC);
    cv::exp(plane, plane);
    sum += plane;
  }
  for (auto& plane : planes) plane /= sum;
  cv::Mat merged;
  cv::merge(planes, merged);
  return merged;
}

/// Per-class edge probabilities: the clamped gradient magnitude of each class probability plane.
cv::Mat classEdgeProbabilities(const cv::Mat& probabilities) {
  std::vector<cv::Mat> planes;
  cv::split(probabilities, planes);
  for (auto& plane : planes) {
    cv::Mat gx, gy;
    cv::Sobel(plane, gx, CV_32F, 1, 0);
    cv::Sobel(plane, gy, CV_32F, 0, 1);
    cv::magnitude(gx, gy, plane);
    cv::min(plane * 0.5, 1.0, plane);
  }
  cv::Mat merged;
  cv::merge(planes, merged);
  return merged;
}

cv::Mat labelsWithConfidence(const cv::Mat& probabilities) {
  cv::Mat labels(probabilities.size(), CV_8UC2);
  const int c = probabilities.channels();
  for (int y = 0; y < labels.rows; ++y)
    for (int x = 0; x < labels.cols; ++x) {
      const float* p = probabilities.ptr<float>(y) + x * c;
      const auto best = std::max_element(p, p + c) - p;
      labels.at<cv::Vec2b>(y, x) = cv::Vec2b(static_cast<std::uint8_t>(best), cv::saturate_cast<std::uint8_t>(255.0f * p[best]));
    }
  return labels;
}

cv::Mat bitmaskWithStrength(const cv::Mat& edge_probabilities, float threshold) {
  cv::Mat bitmask(edge_probabilities.size(), CV_8UC4);
  const int c = edge_probabilities.channels();
  for (int y = 0; y < bitmask.rows; ++y)
    for (int x = 0; x < bitmask.cols; ++x) {
      const float* p = edge_probabilities.ptr<float>(y) + x * c;
      std::uint32_t bits = 0;
      for (int k = 0; k < c; ++k) bits |= p[k] >= threshold ? 1u << k : 0u;
      bitmask.at<cv::Vec4b>(y, x) = cv::Vec4b(bits & 0xff, (bits >> 8) & 0xff, (bits >> 16) & 0xff,
                                              cv::saturate_cast<std::uint8_t>(255.0f * *std::max_element(p, p + c)));
    }
  return bitmask;
}

/// The segmenter's class probabilities of the frame, timed (median of `runs` after a warm-up); a
/// synthetic stand-in without the model. Returns the segmenter's error.
std::string classProbabilities(const std::string& model_path, const cv::Mat& gray, int classes, int runs, cv::Mat* probabilities) {
  if (!std::filesystem::exists(model_path)) {
    std::printf("(no segmenter model at %s: synthetic class probabilities)\n", model_path.c_str());
    *probabilities = syntheticProbabilities(classes);
    return "";
  }
  SegmenterOptions options;
  options.model_path = model_path;
  Segmenter segmenter(options, classes);
  if (!segmenter.ok()) return segmenter.error();
  segmenter.segment(gray, CV_32F, probabilities);  // warm-up
  const double ms = medianMs(runs, [&] { segmenter.segment(gray, CV_32F, probabilities); });
  cv::Mat labels;
  const double labels_ms = medianMs(runs, [&] { segmenter.segmentLabels(gray, &labels); });
  std::printf("segmenter %s, input %dx%d, %d OpenCV threads: median %.1f ms per frame with every class's probability, "
              "%.1f ms with labels (%d runs)\n",
              model_path.c_str(), options.input_width, options.input_height, cv::getNumThreads(), ms, labels_ms, runs);
  return "";
}

/// One intake mode with one form of class input.
struct IntakeRow {
  IntakeMode mode;
  const char* input;
  ClassEvidence evidence;
};

/// Times the row's edge extraction and point sample over `runs` (median thread CPU time, so that
/// other processes on the machine do not inflate the figures) and prints its line.
std::string timeIntake(const IntakeRow& row, const cv::Mat& gray, int runs) {
  const PointSampler sampler{PointSamplerOptions()};
  SemanticEdgeOptions options;
  options.mode = row.mode;
  const SemanticEdgeExtractor extractor(options);
  EdgeSet edges;
  PointSample sample;
  std::string error;
  std::vector<double> extract_ms, sample_ms;
  for (int i = 0; i < runs; ++i) {
    const double start = threadCpuMs();
    if (ExtractionError e = extractor.extract(gray, row.evidence, cv::Mat(), &edges)) error = e.reason + ": " + e.detail;
    const double extracted = threadCpuMs();
    sample = sampler.sample(gray, edges.view());
    extract_ms.push_back(extracted - start);
    sample_ms.push_back(threadCpuMs() - extracted);
  }
  if (!error.empty()) return error;
  std::size_t multi = 0;
  for (std::uint32_t mask : edges.class_mask) multi += __builtin_popcount(mask) > 1;
  std::printf("  %-15s %-27s %6.2f ms = edges+classes %5.2f + sample %5.2f  (%zu edges, %zu with 2+ classes, %zu + %zu sampled)\n",
              toString(row.mode), row.input, median(extract_ms) + median(sample_ms), median(extract_ms), median(sample_ms),
              edges.size(), multi, sample.edge_indices.size(), sample.support_u.size());
  return "";
}

/// Reading a precomputed class map (segment_sequence's labels PNG) and carrying one to the next
/// frame (class_maps newest), each timed over `runs`.
std::string timeClassMaps(const cv::Mat& probabilities, const cv::Mat& gray, const cv::Mat& next_gray, int runs) {
  const std::string path = (std::filesystem::temp_directory_path() / "benchmark_intake_labels.png").string();
  if (std::string error = writeClassLabelsPng(path, probabilities); !error.empty()) return error;
  cv::Mat labels;
  std::string error;
  const double read_ms = medianMs(runs, [&] { error = readClassLabelsPng(path, &labels); });
  std::filesystem::remove(path);
  if (!error.empty()) return error;
  ClassMapCarrier carrier;
  ClassEvidence evidence{ClassEvidenceForm::kLabels, labels, probabilities.channels()}, carried;
  double age = 0.0, t = 0.0;
  int frame = 0;
  carrier.addImage(t, gray);
  carrier.setClassMap(t, evidence);
  const double carry_ms = medianMs(runs, [&] {
    carrier.addImage(t += 0.1, (++frame & 1) ? next_gray : gray);
    carrier.carryTo(t, &carried, &age);
  });
  std::printf("precomputed labels (segment_sequence's PNG): read %.1f ms; a class map carried to the next frame "
              "(optical flow and remap): %.1f ms; %d OpenCV threads, median of %d runs\n", read_ms, carry_ms, cv::getNumThreads(), runs);
  return "";
}

}  // namespace

const char* const kUsage =
    "usage: benchmark_intake [--image PNG] [--segmenter-model PATH] [--runs R] [--segmenter-runs S]\n"
    "  defaults: KITTI 06 frame 0 and ENet from ../shared (a test pattern and synthetic class\n"
    "  probabilities without them), 30 intake runs, 5 segmenter runs\n";

int main(int argc, char** argv) {
  if (printUsageIfAsked(argc, argv, kUsage)) return 0;
  const std::string shared = SEVO_DEFAULT_SHARED_DIR;
  std::string image_path = shared + "/data/kitti_odometry/sequences/06/image_0/000000.png";
  std::string model_path = shared + "/models/enet_cityscapes/model-best.opencv.net";
  int runs = 30, segmenter_runs = 5;
  std::string runs_text, segmenter_runs_text;
  std::string error = parseFlags(argc, argv,
                                 {{"--image", &image_path}, {"--segmenter-model", &model_path}, {"--runs", &runs_text},
                                  {"--segmenter-runs", &segmenter_runs_text}},
                                 {});
  if (error.empty()) error = parseNumber("--runs", runs_text, &runs);
  if (error.empty()) error = parseNumber("--segmenter-runs", segmenter_runs_text, &segmenter_runs);
  if (!error.empty()) {
    std::fprintf(stderr, "benchmark_intake: %s\n%s", error.c_str(), kUsage);
    return 2;
  }
  if (runs < 1 || segmenter_runs < 1) {
    std::fprintf(stderr, "benchmark_intake: need runs >= 1 and segmenter-runs >= 1\n");
    return 2;
  }
  cv::Mat gray = cv::imread(image_path, cv::IMREAD_GRAYSCALE);
  if (gray.empty()) {
    std::printf("(no image at %s: using the generated test pattern)\n", image_path.c_str());
    gray = renderTestPattern(0, kWidth, kHeight);
  }
  cv::resize(gray, gray, cv::Size(kWidth, kHeight), 0, 0, cv::INTER_LINEAR);
  const ClassTable table = ClassTable::cityscapes();
  const int classes = table.size();

  cv::Mat probabilities;
  error = classProbabilities(model_path, gray, classes, segmenter_runs, &probabilities);
  if (!error.empty()) {
    std::fprintf(stderr, "benchmark_intake: %s\n", error.c_str());
    return 1;
  }
  cv::Mat probabilities8, edge_probabilities8;
  probabilities.convertTo(probabilities8, CV_8U, 255.0);
  const cv::Mat edge_probabilities = classEdgeProbabilities(probabilities);
  edge_probabilities.convertTo(edge_probabilities8, CV_8U, 255.0);
  const cv::Mat labels = labelsWithConfidence(probabilities);
  const cv::Mat bitmask = bitmaskWithStrength(edge_probabilities, 0.3f);
  // The next frame of the sequence when there is one, for the carried class map.
  std::filesystem::path next_path = image_path;
  next_path.replace_filename("000001.png");
  cv::Mat next_gray = cv::imread(next_path.string(), cv::IMREAD_GRAYSCALE);
  if (next_gray.empty()) next_gray = gray;
  cv::resize(next_gray, next_gray, gray.size(), 0, 0, cv::INTER_LINEAR);
  error = timeClassMaps(probabilities8, gray, next_gray, runs);
  if (!error.empty()) {
    std::fprintf(stderr, "benchmark_intake: %s\n", error.c_str());
    return 1;
  }

  cv::setNumThreads(1);
  std::printf("intake of a %dx%d frame, %d classes, one core, median thread CPU time of %d runs:\n",
              kWidth, kHeight, classes, runs);
  const std::vector<IntakeRow> rows = {
      {IntakeMode::kCanny, "-", {}},
      {IntakeMode::kFused, "32FC19 probabilities", {ClassEvidenceForm::kProbabilities, probabilities, classes}},
      {IntakeMode::kFused, "8UC19 probabilities", {ClassEvidenceForm::kProbabilities, probabilities8, classes}},
      {IntakeMode::kFused, "8UC2 labels+confidence", {ClassEvidenceForm::kLabels, labels, classes}},
      {IntakeMode::kSemanticEdges, "32FC19 edge probabilities", {ClassEvidenceForm::kProbabilities, edge_probabilities, classes}},
      {IntakeMode::kSemanticEdges, "8UC19 edge probabilities", {ClassEvidenceForm::kProbabilities, edge_probabilities8, classes}},
      {IntakeMode::kSemanticEdges, "8UC4 bitmask+strength", {ClassEvidenceForm::kBitmask, bitmask, classes}},
  };
  for (const IntakeRow& row : rows) {
    error = timeIntake(row, gray, runs);
    if (!error.empty()) {
      std::fprintf(stderr, "benchmark_intake: %s (%s): %s\n", toString(row.mode), row.input, error.c_str());
      return 1;
    }
  }
  return 0;
}
