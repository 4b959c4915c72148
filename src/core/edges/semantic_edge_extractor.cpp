#include "semantic_edge_vo/edges/semantic_edge_extractor.h"

#include <algorithm>
#include <sstream>

namespace semantic_edge_vo {
namespace {

/// Nearest pixel index to a coordinate, clamped to [0, size).
inline int nearestPixel(float coordinate, int size) {
  return std::min(nearestPixelIndex(std::max(coordinate, 0.0f)), size - 1);
}

/// The pixels nearest to edge i's position and to it -+ distance along its normal.
PixelTriple pixelsAcross(const EdgeSet& edges, std::size_t i, float distance, cv::Size size) {
  PixelTriple pixels;
  for (int k = 0; k < 3; ++k) {
    const float side = static_cast<float>(k - 1) * distance;
    pixels[static_cast<std::size_t>(k)] = {nearestPixel(edges.u[i] + side * edges.normal_x[i], size.width),
                                            nearestPixel(edges.v[i] + side * edges.normal_y[i], size.height)};
  }
  return pixels;
}

/// Calls visit(i, mask, best) for every edge i in order, with the class mask of the evidence at its
/// pixelsAcross() and the highest value. The look-ups are scattered over up to 35 MB: the values of
/// the edge kFetchAhead further on are requested in advance, so that several memory fetches overlap
/// instead of each stalling the loop. With `check`, every row of the values is also checked for
/// invalid probabilities (ClassEvidence::invalidInRows), a band at a time just ahead of the edges'
/// rows (edges come in image order), so that the values come from memory once for both; returns
/// whether any is invalid (the masks are meaningless then).
template <typename Visit>
bool forEachClassMask(const ClassEvidence& classes, const EdgeSet& edges, float distance, float threshold, bool check,
                      Visit visit) {
  constexpr std::size_t kFetchAhead = 8;
  constexpr int kBandRows = 8;
  const cv::Size size = classes.values.size();
  const int reach = static_cast<int>(distance) + 3;  // past an edge's row, the end of the rows its look-ups read
  int checked = check ? 0 : size.height;             // rows [0, checked) are checked
  bool invalid = false;
  for (std::size_t i = 0; i < edges.size(); ++i) {
    const std::size_t ahead = std::min(i + kFetchAhead, edges.size() - 1);
    const int needed = std::min(size.height, static_cast<int>(edges.v[ahead]) + reach);
    if (needed > checked) {
      const int band_end = std::min(size.height, needed + kBandRows);
      invalid |= classes.invalidInRows(checked, band_end);
      checked = band_end;
    }
    if (ahead > i) classes.prefetch(pixelsAcross(edges, ahead, distance, size));
    float best = 0.0f;
    const std::uint32_t mask = classes.classMaskAcross(pixelsAcross(edges, i, distance, size), threshold, &best);
    visit(i, mask, best);
  }
  return classes.invalidInRows(checked, size.height) || invalid;
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
  // The class values are checked in extract's pass over them (the edge map's here: it is small).
  if (!fused || edge_probability.empty()) return {};
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
    if (!assignFusedClasses(classes, edges)) {
      *edges = EdgeSet();
      return invalidProbabilities(classes.invalidValueCount(), "class");
    }
  } else {
    std::size_t invalid = 0;
    const cv::Mat probability = classes.edgeProbability(&invalid);
    if (invalid) return invalidProbabilities(invalid, "class");
    *edges = thinEdgeProbability(probability, gray, options_.thinning);
    assignEdgeClasses(classes, edges);
  }
  return {};
}

bool SemanticEdgeExtractor::assignFusedClasses(const ClassEvidence& classes, EdgeSet* edges) const {
  // Edges without any class evidence (unlabeled pixels, all probabilities 0) get no class: they are
  // dropped, keeping the order of the others (kept <= i: in place). The strength stays the edge's
  // own: scaled by the class probability it ranked confidently labelled edges above strong ones in
  // the point sample, and tracking needs strong ones (KITTI 06, ENet on the gray images, no edge
  // residuals: Sim(3) ATE 0.93 m scaled, 0.05 m unscaled, medians over three point budgets).
  std::size_t kept = 0;
  const bool invalid = forEachClassMask(
      classes, *edges, static_cast<float>(options_.side_distance), static_cast<float>(options_.class_threshold), true,
      [&](std::size_t i, std::uint32_t mask, float) {
        if (!mask) return;
        edges->u[kept] = edges->u[i];
        edges->v[kept] = edges->v[i];
        edges->normal_x[kept] = edges->normal_x[i];
        edges->normal_y[kept] = edges->normal_y[i];
        edges->strength[kept] = edges->strength[i];
        edges->class_mask[kept] = mask;
        ++kept;
      });
  for (auto* values : {&edges->u, &edges->v, &edges->normal_x, &edges->normal_y, &edges->strength}) values->resize(kept);
  edges->class_mask.resize(kept);
  return !invalid;
}

void SemanticEdgeExtractor::assignEdgeClasses(const ClassEvidence& classes, EdgeSet* edges) const {
  // Checked already, by edgeProbability().
  forEachClassMask(classes, *edges, 1.0f, static_cast<float>(options_.class_threshold), false,
                   [&](std::size_t i, std::uint32_t mask, float) { edges->class_mask[i] = mask; });
}

}  // namespace semantic_edge_vo
