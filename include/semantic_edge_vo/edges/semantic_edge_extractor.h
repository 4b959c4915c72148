#pragma once
#include <cstdint>
#include <string>

#include <opencv2/core/mat.hpp>

#include "semantic_edge_vo/edges/canny_edge_detector.h"
#include "semantic_edge_vo/edges/class_evidence.h"
#include "semantic_edge_vo/edges/edge_probability_thinning.h"
#include "semantic_edge_vo/common/edge_set.h"

namespace semantic_edge_vo {

/// Where edges and their classes come from (paper III-A, IV-C).
enum class IntakeMode {
  kCanny,          ///< edges from the image alone, one class
  kFused,          ///< an edge map (Canny or a learned edge probability) x class probabilities
  kSemanticEdges,  ///< per-class edge probabilities (CASENet/SEAL style)
};
bool parseIntakeMode(const std::string& text, IntakeMode* mode);
const char* toString(IntakeMode mode);

struct SemanticEdgeOptions {
  IntakeMode mode = IntakeMode::kCanny;
  double class_threshold = 0.3;  ///< class bit set when the class (edge) probability reaches this, [0, 1]
  double side_distance = 2.0;    ///< fused: class probabilities are read this far on both sides of an edge, px
  CannyOptions canny;            ///< canny mode, and fused without a learned edge map
  EdgeThinningOptions thinning;  ///< learned edge maps (fused with an edge map, semantic_edges)

  std::string validate() const;
};

/// What went wrong with an input, by name (the intake logs it and drops the frame).
struct ExtractionError {
  std::string reason;  ///< empty: no error
  std::string detail;  ///< what was expected
  explicit operator bool() const { return !reason.empty(); }
};

/// Thinned edge pixels with class masks, per the intake mode. Class masks always hold the most
/// probable class plus every other class whose probability reaches `class_threshold` (soft
/// multi-label: a car/road boundary pixel is in both).
///  - canny: Canny edges, class mask 1 (the single class "edge").
///  - fused: edges from Canny or a learned edge map; class probabilities are read at the pixel and
///    `side_distance` px along the normal on both sides, the maximum per class counts (a boundary
///    pixel sees both regions). Strength stays the edge strength (the point sampler ranks by it;
///    scaled by the class probability it preferred confidently labelled edges to strong ones). Edges
///    without any class evidence there (unlabeled, every probability 0) are dropped.
///  - semantic_edges: the maximum over per-class edge probabilities is thinned; the class mask
///    comes from the per-class values at the pixel and its two neighbours along the normal.
/// Only edge pixels and their sides are looked up, never full-resolution per-class products.
class SemanticEdgeExtractor {
 public:
  explicit SemanticEdgeExtractor(const SemanticEdgeOptions& options) : options_(options) {}

  /// @param[in] gray CV_8UC1 image
  /// @param[in] classes class evidence of that image (ignored in canny mode): fused takes
  ///            probabilities or labels, semantic_edges per-class edge probabilities or a bitmask
  /// @param[in] edge_probability fused only: CV_32FC1 in [0, 1] or CV_8UC1 (x 255); empty: Canny
  /// @param[out] edges the result (left empty on error)
  ExtractionError extract(const cv::Mat& gray, const ClassEvidence& classes, const cv::Mat& edge_probability,
                          EdgeSet* edges) const;

  /// Canny edges in any mode, with `class_mask` on every pixel (fallback when classes are missing).
  EdgeSet cannyEdges(const cv::Mat& gray, std::uint32_t class_mask) const;

 private:
  ExtractionError checkInputs(const cv::Mat& gray, const ClassEvidence& classes, const cv::Mat& edge_probability) const;
  /// False when a class probability is invalid (NaN or outside [0, 1]), found in the same pass.
  bool assignFusedClasses(const ClassEvidence& classes, EdgeSet* edges) const;
  void assignEdgeClasses(const ClassEvidence& classes, EdgeSet* edges) const;

  SemanticEdgeOptions options_;
};

}  // namespace semantic_edge_vo
