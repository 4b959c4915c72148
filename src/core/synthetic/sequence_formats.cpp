#include "semantic_edge_vo/synthetic/sequence_formats.h"

#include <cmath>
#include <cstring>

#include <opencv2/imgcodecs.hpp>

namespace semantic_edge_vo {
namespace synthetic {

cv::Mat encodeDepth(const cv::Mat& depth) {
  CV_Assert(depth.type() == CV_32FC1);
  cv::Mat encoded(depth.size(), CV_16UC1);
  for (int y = 0; y < depth.rows; ++y) {
    const float* in = depth.ptr<float>(y);
    auto* out = encoded.ptr<std::uint16_t>(y);
    for (int x = 0; x < depth.cols; ++x) {
      const double value = std::round(in[x] * kDepthScale);
      out[x] = in[x] > 0.0f && value <= 65535.0 ? static_cast<std::uint16_t>(value) : 0;
    }
  }
  return encoded;
}

cv::Mat decodeDepth(const cv::Mat& encoded) {
  CV_Assert(encoded.type() == CV_16UC1);
  cv::Mat depth;
  encoded.convertTo(depth, CV_32FC1, 1.0 / kDepthScale);
  return depth;
}

cv::Mat packEdgeBitmask(const SemanticNetworkOutput& semantics) {
  CV_Assert(semantics.edge_strength.type() == CV_8UC1 && semantics.edge_classes.type() == CV_32SC1);
  cv::Mat packed(semantics.edge_strength.size(), CV_8UC4);
  for (int y = 0; y < packed.rows; ++y) {
    const std::uint8_t* strength = semantics.edge_strength.ptr<std::uint8_t>(y);
    const std::int32_t* classes = semantics.edge_classes.ptr<std::int32_t>(y);
    auto* out = packed.ptr<cv::Vec4b>(y);
    for (int x = 0; x < packed.cols; ++x) {
      const auto bits = static_cast<std::uint32_t>(classes[x]);
      out[x] = cv::Vec4b(static_cast<std::uint8_t>(bits), static_cast<std::uint8_t>(bits >> 8),
                         static_cast<std::uint8_t>(bits >> 16), strength[x]);
    }
  }
  return packed;
}

void unpackEdgeBitmask(const cv::Mat& packed, cv::Mat* strength, cv::Mat* classes) {
  CV_Assert(packed.type() == CV_8UC4);
  strength->create(packed.size(), CV_8UC1);
  classes->create(packed.size(), CV_32SC1);
  for (int y = 0; y < packed.rows; ++y) {
    const auto* in = packed.ptr<cv::Vec4b>(y);
    for (int x = 0; x < packed.cols; ++x) {
      classes->at<std::int32_t>(y, x) = static_cast<std::int32_t>(in[x][0] | in[x][1] << 8 | in[x][2] << 16);
      strength->at<std::uint8_t>(y, x) = in[x][3];
    }
  }
}

cv::Mat classLabels(const SemanticNetworkOutput& semantics) {
  cv::Mat labels(semantics.class_probability.size(), CV_8UC2);
  const int pairs[] = {0, 0, 1, 1};
  cv::mixChannels(&semantics.class_probability, 1, &labels, 1, pairs, 2);
  return labels;
}

std::vector<std::uint8_t> encodePng(const cv::Mat& image) {
  std::vector<std::uint8_t> bytes;
  cv::imencode(".png", image, bytes, {cv::IMWRITE_PNG_COMPRESSION, 1, cv::IMWRITE_PNG_STRATEGY, cv::IMWRITE_PNG_STRATEGY_RLE});
  return bytes;
}

const std::vector<std::uint8_t>* EncodedFrame::find(const std::string& folder) const {
  for (const auto& file : files)
    if (file.first == folder) return &file.second;
  return nullptr;
}

EncodedFrame encodeFrame(const SyntheticFrame& frame, bool semantics, const ClassTable& classes) {
  EncodedFrame encoded;
  encoded.index = frame.index;
  encoded.files = {{"image_0", encodePng(frame.gray)},
                   {"image_2", encodePng(frame.color)},
                   {"depth", encodePng(encodeDepth(frame.depth))},
                   {"semantic", encodePng(frame.class_id)},
                   {"semantic_rgb", encodePng(colorizeClasses(frame.class_id, classes))},
                   {"dynamic", encodePng(frame.dynamic)}};
  if (semantics) {
    encoded.files.emplace_back("edge_bitmask", encodePng(packEdgeBitmask(frame.semantics)));
    encoded.files.emplace_back("class_probability", encodePng(frame.semantics.class_probability));
  }
  return encoded;
}

cv::Mat colorizeClasses(const cv::Mat& class_id, const ClassTable& table) {
  CV_Assert(class_id.type() == CV_8UC1);
  cv::Mat colour(class_id.size(), CV_8UC3, cv::Scalar::all(0));
  for (int y = 0; y < class_id.rows; ++y) {
    const std::uint8_t* in = class_id.ptr<std::uint8_t>(y);
    auto* out = colour.ptr<cv::Vec3b>(y);
    for (int x = 0; x < class_id.cols; ++x)
      if (in[x] < table.size()) {
        const auto& rgb = table[in[x]].rgb;
        out[x] = cv::Vec3b(rgb[2], rgb[1], rgb[0]);
      }
  }
  return colour;
}

}  // namespace synthetic
}  // namespace semantic_edge_vo
