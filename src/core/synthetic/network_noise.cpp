#include "semantic_edge_vo/synthetic/network_noise.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include <opencv2/imgproc.hpp>

#include "semantic_edge_vo/support/command_line.h"
#include "semantic_edge_vo/synthetic/noise.h"
#include "semantic_edge_vo/synthetic/random.h"

namespace semantic_edge_vo {
namespace synthetic {
namespace {

std::uint32_t salted(std::uint64_t seed, std::uint64_t salt) { return static_cast<std::uint32_t>(hashCombine(seed, salt)); }

std::uint32_t remapBits(std::uint32_t mask) {
  std::uint32_t out = 0;
  for (; mask; mask &= mask - 1u) out |= 1u << confusableClass(__builtin_ctz(mask));
  return out;
}

void confuseLabels(double strength, std::uint64_t seed, SemanticNetworkOutput* out) {
  const cv::Mat field = smoothNoiseField(out->edge_strength.cols, out->edge_strength.rows, 50.0, salted(seed, 1));
  const auto threshold = static_cast<float>(1.0 - 0.6 * strength);
  for (int y = 0; y < field.rows; ++y) {
    const float* f = field.ptr<float>(y);
    auto* probability = out->class_probability.ptr<cv::Vec4b>(y);
    auto* classes = out->edge_classes.ptr<std::int32_t>(y);
    for (int x = 0; x < field.cols; ++x) {
      if (f[x] <= threshold) continue;
      const float depth = std::min(1.0f, (f[x] - threshold) / std::max(0.05f, 1.0f - threshold));
      const int wrong = confusableClass(probability[x][0]);
      const auto confidence = static_cast<std::uint8_t>(std::lround(255.0f * (0.5f + 0.4f * depth)));
      probability[x] = cv::Vec4b(static_cast<std::uint8_t>(wrong), confidence, probability[x][0],
                                 static_cast<std::uint8_t>(250 - confidence));
      classes[x] = static_cast<std::int32_t>(remapBits(static_cast<std::uint32_t>(classes[x])));
    }
  }
}

/// OR of the masks within `radius` pixels (a square): the labels of thickened edges.
void dilateMasks(int radius, cv::Mat* masks) {
  cv::Mat horizontal(masks->size(), CV_32SC1);
  for (int y = 0; y < masks->rows; ++y) {
    const auto* in = masks->ptr<std::int32_t>(y);
    auto* out = horizontal.ptr<std::int32_t>(y);
    for (int x = 0; x < masks->cols; ++x) {
      std::int32_t m = 0;
      for (int dx = std::max(0, x - radius); dx <= std::min(masks->cols - 1, x + radius); ++dx) m |= in[dx];
      out[x] = m;
    }
  }
  for (int y = 0; y < masks->rows; ++y) {
    auto* out = masks->ptr<std::int32_t>(y);
    for (int x = 0; x < masks->cols; ++x) {
      std::int32_t m = 0;
      for (int dy = std::max(0, y - radius); dy <= std::min(masks->rows - 1, y + radius); ++dy)
        m |= horizontal.at<std::int32_t>(dy, x);
      out[x] = m;
    }
  }
}

void blurEdges(double strength, SemanticNetworkOutput* out) {
  const int radius = static_cast<int>(std::lround(2.0 * strength));
  const double sigma = 1.5 * strength;
  if (radius > 0) cv::dilate(out->edge_strength, out->edge_strength, cv::Mat::ones(2 * radius + 1, 2 * radius + 1, CV_8U));
  if (sigma > 0.3) cv::GaussianBlur(out->edge_strength, out->edge_strength, cv::Size(0, 0), sigma);
  dilateMasks(radius + static_cast<int>(std::ceil(3.0 * sigma)), &out->edge_classes);
  // Blur tails beyond the label dilation are dropped: every edge pixel keeps a label.
  out->edge_strength.setTo(0, out->edge_classes == 0);
  out->edge_classes.setTo(0, out->edge_strength == 0);
}

void dropEdges(double strength, std::uint64_t seed, SemanticNetworkOutput* out) {
  const cv::Mat field = smoothNoiseField(out->edge_strength.cols, out->edge_strength.rows, 30.0, salted(seed, 2));
  // Value noise is bell-shaped around 0.5: this maps the strength to roughly that fraction removed.
  const auto threshold = static_cast<float>(0.5 + 0.45 * std::tan(2.5 * (strength - 0.5)) / std::tan(1.25));
  for (int y = 0; y < field.rows; ++y) {
    const float* f = field.ptr<float>(y);
    auto* edge = out->edge_strength.ptr<std::uint8_t>(y);
    auto* classes = out->edge_classes.ptr<std::int32_t>(y);
    for (int x = 0; x < field.cols; ++x) {
      const float keep = std::clamp((f[x] - threshold) * 20.0f + 0.5f, 0.0f, 1.0f);
      edge[x] = static_cast<std::uint8_t>(std::lround(edge[x] * keep));
      if (edge[x] == 0) classes[x] = 0;
    }
  }
}

void addSpuriousEdges(double strength, std::uint64_t seed, SemanticNetworkOutput* out) {
  const int width = out->edge_strength.cols, height = out->edge_strength.rows;
  const cv::Mat lines = smoothNoiseField(width, height, 20.0, salted(seed, 3));
  const cv::Mat patches = smoothNoiseField(width, height, 90.0, salted(seed, 4));
  const auto threshold = static_cast<float>(1.0 - 0.7 * strength);
  for (int y = 1; y < height - 1; ++y) {
    const float* l = lines.ptr<float>(y);
    const float* below = lines.ptr<float>(y + 1);
    const float* p = patches.ptr<float>(y);
    auto* edge = out->edge_strength.ptr<std::uint8_t>(y);
    auto* classes = out->edge_classes.ptr<std::int32_t>(y);
    const auto* probability = out->class_probability.ptr<cv::Vec4b>(y);
    for (int x = 0; x < width - 1; ++x) {
      if (p[x] <= threshold) continue;
      // Pixels where the field crosses 0.5 towards a right or lower neighbour: a 1-2 px wide curve.
      const bool crossing = (l[x] - 0.5f) * (l[x + 1] - 0.5f) <= 0.0f || (l[x] - 0.5f) * (below[x] - 0.5f) <= 0.0f;
      if (!crossing) continue;
      const auto value = static_cast<std::uint8_t>(std::lround(255.0f * std::min(0.9f, 0.3f + (p[x] - threshold) * 3.0f)));
      if (value > edge[x]) edge[x] = value;
      classes[x] |= static_cast<std::int32_t>(1u << probability[x][0]);
    }
  }
}

}  // namespace

std::string NetworkNoiseOptions::validate() const {
  std::ostringstream error;
  const double values[4] = {label_confusion, edge_blur, missed_edges, spurious_edges};
  const char* names[4] = {"label_confusion", "edge_blur", "missed_edges", "spurious_edges"};
  for (int i = 0; i < 4; ++i)
    if (!(values[i] >= 0.0 && values[i] <= 1.0)) {
      error << names[i] << " must be in [0, 1] (got " << values[i] << ")";
      break;
    }
  return error.str();
}

const std::vector<std::string>& noiseFlags() {
  static const std::vector<std::string> flags = {"--label-confusion", "--edge-blur", "--missed-edges", "--spurious-edges"};
  return flags;
}

bool parseNoiseFlag(const std::string& flag, const std::string& value, NetworkNoiseOptions* options, std::string* error) {
  double* const targets[] = {&options->label_confusion, &options->edge_blur, &options->missed_edges, &options->spurious_edges};
  for (std::size_t i = 0; i < noiseFlags().size(); ++i) {
    if (flag != noiseFlags()[i]) continue;
    *error = parseNumber(flag, value, targets[i]);
    return true;
  }
  return false;
}

void applyNetworkNoise(const NetworkNoiseOptions& options, std::uint64_t seed, SemanticNetworkOutput* output) {
  if (options.label_confusion > 0.0) confuseLabels(options.label_confusion, seed, output);
  if (options.edge_blur > 0.0) blurEdges(options.edge_blur, output);
  if (options.missed_edges > 0.0) dropEdges(options.missed_edges, seed, output);
  if (options.spurious_edges > 0.0) addSpuriousEdges(options.spurious_edges, seed, output);
}

}  // namespace synthetic
}  // namespace semantic_edge_vo
