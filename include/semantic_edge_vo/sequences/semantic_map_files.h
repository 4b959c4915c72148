#pragma once
#include <string>

#include <opencv2/core/mat.hpp>

namespace semantic_edge_vo {

// Per-frame semantics saved by an external network as PNG files, read into the compact forms that
// EdgeIntake takes (docs/synthetic_sequences.md). Both return "" or what is wrong, naming the file.

/// Class labels (`class_format: labels`): an 8-bit PNG with 1 channel (class index per pixel,
/// confidence 1: CV_8UC1 out) or 4 channels whose first two, in cv::imread order, are the class
/// index and its confidence x 255 (the synthetic `class_probability/` layout: CV_8UC2 out).
std::string readClassLabelsPng(const std::string& path, cv::Mat* labels);

/// Writes per-class probabilities (CV_8UC(C), probability x 255, as the Segmenter gives them; C at
/// most 255) in the 4-channel layout readClassLabelsPng() reads, that of synthetic sequences'
/// `class_probability/`: cv::imwrite channels (most probable class, its probability x 255, second
/// class, its probability x 255), ties going to the lower class. "" or what is wrong.
std::string writeClassLabelsPng(const std::string& path, const cv::Mat& probabilities);

/// Edge classes and strength (`class_format: bitmask`): an 8-bit 4-channel PNG, cv::imread channels
/// 0-2 = class bits 0-23, channel 3 = edge probability x 255 (the synthetic `edge_bitmask/` layout).
/// CV_8UC4 out.
std::string readEdgeBitmaskPng(const std::string& path, cv::Mat* bitmask);

}  // namespace semantic_edge_vo
