#pragma once
#include <string>

#include <opencv2/core/mat.hpp>

namespace semantic_edge_vo {

/// How per-pixel class evidence is laid out (the forms EdgeIntake accepts on its class topic).
enum class ClassEvidenceForm {
  kProbabilities,  ///< C channels, channel c = class c: CV_32FC(C) in [0, 1] or CV_8UC(C) (probability x 255)
  kLabels,         ///< compact: CV_8UC1 class index, or CV_8UC2 (class index, confidence x 255); index >= C: unlabeled
  kBitmask,        ///< compact: CV_8UC4, bytes 0..2 class bits 0..23 (bit c = class c), byte 3 edge strength x 255
};

/// Parses "probabilities" | "labels" | "bitmask"; false when unknown.
bool parseClassEvidenceForm(const std::string& text, ClassEvidenceForm* form);
const char* toString(ClassEvidenceForm form);

/// Per-pixel class evidence of one image at its resolution: class probabilities (fused intake) or
/// per-class edge probabilities (semantic_edges intake). A view: `values` may wrap a message buffer.
struct ClassEvidence {
  ClassEvidenceForm form = ClassEvidenceForm::kProbabilities;
  cv::Mat values;   ///< layout per `form`
  int classes = 0;  ///< C, the size of the class table the evidence refers to

  /// Empty when the layout fits a `image_size` image and `classes` classes; otherwise the reason's
  /// name (`channel_count_mismatch`, `size_mismatch`, `unsupported_layout`), `detail` says what was
  /// expected. Values are not read here (see invalidValueCount()).
  std::string checkLayout(cv::Size image_size, std::string* detail) const;
  /// Number of NaN, negative or above-1 probabilities (32-bit float form only; 8-bit forms cannot
  /// hold them). Scans the whole image (about 35 MB at 1241x376x19 floats, ~2 ms with SIMD); counts
  /// one by one only when something is wrong.
  std::size_t invalidValueCount() const;

  /// Probability (or edge probability) of each class at pixel (x, y), written to out[0..classes).
  /// kLabels: the confidence for the labelled class, 0 for the others; kBitmask: 1 for set bits.
  void probabilitiesAt(int x, int y, float* out) const;
  /// Class-agnostic edge probability, CV_32FC1 at full resolution: the maximum over classes
  /// (kProbabilities), the strength byte / 255 (kBitmask). Not defined for kLabels.
  /// @param[out] invalid if given, invalidValueCount() found in the same pass over the values
  cv::Mat edgeProbability(std::size_t* invalid = nullptr) const;
};

}  // namespace semantic_edge_vo
