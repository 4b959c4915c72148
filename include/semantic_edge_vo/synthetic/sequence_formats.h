#pragma once
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include <opencv2/core/mat.hpp>

#include "semantic_edge_vo/common/class_table.h"
#include "semantic_edge_vo/synthetic/synthetic_sequence.h"

namespace semantic_edge_vo {
namespace synthetic {

/// Depth PNG unit, KITTI depth style: value = metres x 256 in a uint16, 0 = no depth (sky, or 256 m
/// and beyond). Quantisation 3.9 mm.
constexpr double kDepthScale = 256.0;
/// The largest depth a depth PNG holds, m.
constexpr double kMaxEncodedDepth = 65535.0 / kDepthScale;

/// CV_32FC1 metres -> CV_16UC1 depth PNG image.
cv::Mat encodeDepth(const cv::Mat& depth);
/// CV_16UC1 depth PNG image -> CV_32FC1 metres (0 where unknown).
cv::Mat decodeDepth(const cv::Mat& encoded);

/// Edge classes and strength in the project's compact bitmask form (ClassEvidenceForm::kBitmask,
/// what EdgeIntake reads with class_format: bitmask): CV_8UC4, bytes 0..2 = class bits 0..23
/// (byte 0 = bits 0..7), byte 3 = edge probability x 255. Bits above 23 are dropped (19 classes).
cv::Mat packEdgeBitmask(const SemanticNetworkOutput& semantics);
/// The inverse: strength CV_8UC1 and classes CV_32SC1 from a packed CV_8UC4 image.
void unpackEdgeBitmask(const cv::Mat& packed, cv::Mat* strength, cv::Mat* classes);

/// Most likely class and its confidence, CV_8UC2 (class, probability x 255): the compact labels form
/// (ClassEvidenceForm::kLabels, class_format: labels). Channels 0 and 1 of class_probability.
cv::Mat classLabels(const SemanticNetworkOutput& semantics);

/// PNG bytes of an image (fast settings: zlib level 1, run-length strategy, which suits noisy
/// photographs and flat label maps alike).
std::vector<std::uint8_t> encodePng(const cv::Mat& image);

/// The PNG files of one frame, encoded once for the sequence folder and the bag: (folder, bytes)
/// pairs, folders as in docs/synthetic_sequences.md (image_0, image_2, depth, semantic, ...).
struct EncodedFrame {
  int index = 0;
  std::vector<std::pair<std::string, std::vector<std::uint8_t>>> files;
  /// The bytes for `folder`, or null.
  const std::vector<std::uint8_t>* find(const std::string& folder) const;
};
EncodedFrame encodeFrame(const SyntheticFrame& frame, bool semantics, const ClassTable& classes);

/// Class ids (CV_8UC1) painted with the class table's colours (CV_8UC3, BGR); unknown ids black.
cv::Mat colorizeClasses(const cv::Mat& class_id, const ClassTable& table);

}  // namespace synthetic
}  // namespace semantic_edge_vo
