#pragma once
#include <string>

#include <opencv2/core/mat.hpp>
#include <sensor_msgs/CompressedImage.h>
#include <sensor_msgs/Image.h>

#include "semantic_edge_vo/edges/class_evidence.h"

namespace semantic_edge_vo {

/// Wraps a class map message as class evidence without copying (the message must outlive it).
/// Encodings: probabilities `32FC<C>` or `8UC<C>`; labels `8UC1`/`mono8` or `8UC2`; bitmask `8UC4`.
/// @return empty when usable, else the reason's name (`unsupported_encoding`, `malformed_image`);
///         `detail` says what was expected. Sizes, channel counts and values are checked by the core.
std::string classEvidenceFromImage(const sensor_msgs::Image& msg, ClassEvidenceForm form, int classes,
                                   ClassEvidence* evidence, std::string* detail);

/// Wraps a learned edge probability message (`32FC1`, or `8UC1`/`mono8` as probability x 255), no copy.
std::string edgeProbabilityFromImage(const sensor_msgs::Image& msg, cv::Mat* probability, std::string* detail);

/// Decodes a compressed image (JPEG, PNG: whatever cv::imdecode reads) to mono8 or bgr8.
/// @return empty on success, else `decode_failed` with `detail`.
std::string decodeCompressedImage(const sensor_msgs::CompressedImage& msg, sensor_msgs::ImagePtr* image, std::string* detail);

}  // namespace semantic_edge_vo
