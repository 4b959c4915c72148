#pragma once
#include <array>
#include <cstdint>
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

/// Pixels whose class evidence is pooled: an edge pixel and one pixel on each side of it.
using PixelTriple = std::array<cv::Point, 3>;

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
  /// hold them). Scans the whole image (about 35 MB at 1241x376x19 floats, ~1.1 ms with SIMD, about
  /// the time to read it from memory); counts one by one only when something is wrong.
  std::size_t invalidValueCount() const;
  /// Whether rows [begin, end) hold a NaN, negative or above-1 probability (32-bit float form only).
  bool invalidInRows(int begin, int end) const;

  /// Class mask of the per-class maximum of the probabilities (or edge probabilities) at the pixels:
  /// the most probable class (the first on ties) plus every class reaching `threshold` (in (0, 1]);
  /// 0 when every value is 0. `best` receives the highest value. kLabels: the confidence for the
  /// labelled class, 0 for the others; kBitmask: 1 for set bits. At most ClassTable::kMaxClasses
  /// classes.
  std::uint32_t classMaskAcross(const PixelTriple& pixels, float threshold, float* best) const;
  /// Asks the memory for the values at the pixels, so that a later classMaskAcross() of them need
  /// not wait for them (a hint: reads nothing, changes nothing).
  void prefetch(const PixelTriple& pixels) const;
  /// Class-agnostic edge probability, CV_32FC1 at full resolution: the maximum over classes
  /// (kProbabilities), the strength byte / 255 (kBitmask). Not defined for kLabels.
  /// @param[out] invalid if given, invalidValueCount() found in the same pass over the values
  cv::Mat edgeProbability(std::size_t* invalid = nullptr) const;
};

}  // namespace semantic_edge_vo
