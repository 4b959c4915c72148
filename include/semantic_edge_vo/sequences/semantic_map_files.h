#pragma once
#include <string>

#include <opencv2/core/mat.hpp>

namespace semantic_edge_vo {

// Per-frame semantics saved by an external network as PNG files, read into the compact forms that
// EdgeIntake takes (docs/synthetic_sequences.md). Both return "" or what is wrong, naming the file.

/// Class labels (`class_format: labels`): a PNG with one 16-bit channel, class index + 256 x
/// confidence x 255 (what writeClassLabelsPng writes), one 8-bit channel (class index, confidence 1:
/// CV_8UC1 out), or 4 8-bit channels whose first two, in cv::imread order, are the class index and
/// its confidence x 255 (the synthetic `class_probability/` layout). CV_8UC2 out but for the 8-bit
/// 1-channel form.
std::string readClassLabelsPng(const std::string& path, cv::Mat* labels);

/// Writes the most probable class of per-class probabilities (CV_8UC(C), probability x 255, as the
/// Segmenter gives them; C at most 255), ties going to the lower class, and its probability as one
/// 16-bit channel (class + 256 x probability x 255) that readClassLabelsPng() reads. "" or what is
/// wrong.
std::string writeClassLabelsPng(const std::string& path, const cv::Mat& probabilities);

/// Edge classes and strength (`class_format: bitmask`): an 8-bit 4-channel PNG, cv::imread channels
/// 0-2 = class bits 0-23, channel 3 = edge probability x 255 (the synthetic `edge_bitmask/` layout).
/// CV_8UC4 out.
std::string readEdgeBitmaskPng(const std::string& path, cv::Mat* bitmask);

}  // namespace semantic_edge_vo
