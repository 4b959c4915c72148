#include "semantic_edge_vo/semantic_edge_extractor.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>

#include "semantic_edge_vo/class_table.h"

namespace semantic_edge_vo {
namespace {

using ClassValues = std::array<float, ClassTable::kMaxClasses>;

/// Per-class maximum of the evidence at the pixels nearest to (u, v) and to (u, v) +- distance * n.
void maximumAcross(const ClassEvidence& classes, float u, float v, float nx, float ny, float distance,
                   ClassValues* maximum) {
  ClassValues sample;
  const int c = classes.classes;
  std::fill(maximum->begin(), maximum->begin() + c, 0.0f);
  for (const float side : {-distance, 0.0f, distance}) {
    const int x = std::clamp(static_cast<int>(std::lround(u + side * nx)), 0, classes.values.cols - 1);
    const int y = std::clamp(static_cast<int>(std::lround(v + side * ny)), 0, classes.values.rows - 1);
    classes.probabilitiesAt(x, y, sample.data());
    for (int k = 0; k < c; ++k) (*maximum)[static_cast<std::size_t>(k)] = std::max((*maximum)[static_cast<std::size_t>(k)], sample[static_cast<std::size_t>(k)]);
  }
}

/// The most probable class plus every class at or above the threshold; 0 without any evidence.
/// `best` receives the highest value.
std::uint32_t classMask(const ClassValues& values, int classes, float threshold, float* best) {
  const auto begin = values.begin(), end = values.begin() + classes;
  const auto top = std::max_element(begin, end);
  *best = *top;
  if (*top <= 0.0f) return 0u;
  std::uint32_t mask = 1u << (top - begin);
  for (int k = 0; k < classes; ++k)
    if (values[static_cast<std::size_t>(k)] >= threshold) mask |= 1u << k;
  return mask;
}

ExtractionError invalidProbabilities(std::size_t count, const char* what) {
  return {"invalid_probability", std::to_string(count) + " " + what + " probabilities are NaN or outside [0, 1]"};
}

}  // namespace

bool parseIntakeMode(const std::string& text, IntakeMode* mode) {
  if (text == "canny") *mode = IntakeMode::kCanny;
  else if (text == "fused") *mode = IntakeMode::kFused;
  else if (text == "semantic_edges") *mode = IntakeMode::kSemanticEdges;
  else return false;
  return true;
}

const char* toString(IntakeMode mode) {
  switch (mode) {
    case IntakeMode::kCanny: return "canny";
    case IntakeMode::kFused: return "fused";
    case IntakeMode::kSemanticEdges: return "semantic_edges";
  }
  return "?";
}

std::string SemanticEdgeOptions::validate() const {
  std::ostringstream error;
  if (!(class_threshold > 0.0 && class_threshold <= 1.0))
    error << "class_threshold must be in (0, 1] (got " << class_threshold << ")";
  else if (!(side_distance >= 0.0 && side_distance <= 10.0))
    error << "side_distance must be in [0, 10] px (got " << side_distance << ")";
  if (!error.str().empty()) return error.str();
  const std::string canny_error = canny.validate();
  return canny_error.empty() ? thinning.validate() : canny_error;
}

EdgeSet SemanticEdgeExtractor::cannyEdges(const cv::Mat& gray, std::uint32_t class_mask) const {
  return CannyEdgeDetector(options_.canny).detect(gray, class_mask);
}

ExtractionError SemanticEdgeExtractor::checkInputs(const cv::Mat& gray, const ClassEvidence& classes,
                                                   const cv::Mat& edge_probability) const {
  CV_Assert(gray.type() == CV_8UC1);
  const bool fused = options_.mode == IntakeMode::kFused;
  const bool form_fits = fused ? classes.form != ClassEvidenceForm::kBitmask : classes.form != ClassEvidenceForm::kLabels;
  if (!form_fits)
    return {"unsupported_layout", std::string("the ") + toString(options_.mode) + " intake does not take the " +
                                      toString(classes.form) + " form"};
  ExtractionError error;
  error.reason = classes.checkLayout(gray.size(), &error.detail);
  if (error) return error;
  if (!fused) return {};  // semantic_edges checks the values in its pass over them (extract)
  if (const std::size_t invalid = classes.invalidValueCount()) return invalidProbabilities(invalid, "class");
  if (edge_probability.empty()) return {};
  if (edge_probability.type() != CV_32FC1 && edge_probability.type() != CV_8UC1)
    return {"unsupported_layout", "edge probability must be one channel, 32-bit float or 8-bit"};
  if (edge_probability.size() != gray.size())
    return {"size_mismatch", "edge map is " + std::to_string(edge_probability.cols) + "x" +
                                 std::to_string(edge_probability.rows) + ", image is " + std::to_string(gray.cols) +
                                 "x" + std::to_string(gray.rows)};
  if (const std::size_t invalid = ClassEvidence{ClassEvidenceForm::kProbabilities, edge_probability, 1}.invalidValueCount())
    return invalidProbabilities(invalid, "edge");
  return {};
}

ExtractionError SemanticEdgeExtractor::extract(const cv::Mat& gray, const ClassEvidence& classes,
                                               const cv::Mat& edge_probability, EdgeSet* edges) const {
  *edges = EdgeSet();
  if (options_.mode == IntakeMode::kCanny) {
    *edges = cannyEdges(gray, 1u);
    return {};
  }
  if (ExtractionError error = checkInputs(gray, classes, edge_probability)) return error;
  if (options_.mode == IntakeMode::kFused) {
    if (edge_probability.empty()) {
      *edges = cannyEdges(gray, 0u);
    } else {
      cv::Mat probability = edge_probability;
      if (probability.depth() == CV_8U) edge_probability.convertTo(probability, CV_32F, 1.0 / 255.0);
      *edges = thinEdgeProbability(probability, gray, options_.thinning);
    }
    assignFusedClasses(classes, edges);
  } else {
    std::size_t invalid = 0;
    const cv::Mat probability = classes.edgeProbability(&invalid);
    if (invalid) return invalidProbabilities(invalid, "class");
    *edges = thinEdgeProbability(probability, gray, options_.thinning);
    assignEdgeClasses(classes, edges);
  }
  return {};
}

void SemanticEdgeExtractor::assignFusedClasses(const ClassEvidence& classes, EdgeSet* edges) const {
  ClassValues maximum;
  const auto distance = static_cast<float>(options_.side_distance);
  const auto threshold = static_cast<float>(options_.class_threshold);
  // Edges without any class evidence (unlabeled pixels, all probabilities 0) would get strength 0
  // and no class: they are dropped, keeping the order of the others.
  std::size_t kept = 0;
  for (std::size_t i = 0; i < edges->size(); ++i) {
    maximumAcross(classes, edges->u[i], edges->v[i], edges->normal_x[i], edges->normal_y[i], distance, &maximum);
    float best = 0.0f;
    const std::uint32_t mask = classMask(maximum, classes.classes, threshold, &best);
    if (!mask) continue;
    edges->u[kept] = edges->u[i];
    edges->v[kept] = edges->v[i];
    edges->normal_x[kept] = edges->normal_x[i];
    edges->normal_y[kept] = edges->normal_y[i];
    edges->strength[kept] = edges->strength[i] * best;
    edges->class_mask[kept] = mask;
    ++kept;
  }
  for (auto* values : {&edges->u, &edges->v, &edges->normal_x, &edges->normal_y, &edges->strength}) values->resize(kept);
  edges->class_mask.resize(kept);
}

void SemanticEdgeExtractor::assignEdgeClasses(const ClassEvidence& classes, EdgeSet* edges) const {
  ClassValues maximum;
  const auto threshold = static_cast<float>(options_.class_threshold);
  for (std::size_t i = 0; i < edges->size(); ++i) {
    maximumAcross(classes, edges->u[i], edges->v[i], edges->normal_x[i], edges->normal_y[i], 1.0f, &maximum);
    float best = 0.0f;
    edges->class_mask[i] = classMask(maximum, classes.classes, threshold, &best);
  }
}

}  // namespace semantic_edge_vo
