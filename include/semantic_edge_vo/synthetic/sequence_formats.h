#pragma once
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include <opencv2/core/mat.hpp>

#include "semantic_edge_vo/class_table.h"
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

/// CV_32SC1 class bit masks as a CV_8UC4 image sharing the same bytes: byte k of the little-endian
/// 32-bit mask is channel k as cv::imread returns it (a no-copy view).
cv::Mat maskBytes(const cv::Mat& masks);
/// The inverse: a CV_8UC4 image read with cv::IMREAD_UNCHANGED -> CV_32SC1 masks.
cv::Mat masksFromBytes(const cv::Mat& bytes);

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
