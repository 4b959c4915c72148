#include "semantic_edge_vo/synthetic/semantic_channels.h"

#include <algorithm>
#include <cmath>

#include <opencv2/imgproc.hpp>

namespace semantic_edge_vo {
namespace synthetic {
namespace {

constexpr int kTextureLow = 90;    // Sobel |gx| + |gy| where texture edges start
constexpr int kTextureHigh = 300;  // ... and reach their largest probability
constexpr float kTextureMax = 0.8f;

}  // namespace

float SemanticNetworkOutput::edgeProbability(int k, int x, int y) const {
  const auto mask = static_cast<std::uint32_t>(edge_classes.at<std::int32_t>(y, x));
  return (mask >> k) & 1u ? edge_strength.at<std::uint8_t>(y, x) / 255.0f : 0.0f;
}

cv::Mat SemanticNetworkOutput::topClass() const {
  cv::Mat channel;
  cv::extractChannel(class_probability, channel, 0);
  return channel;
}

cv::Mat SemanticNetworkOutput::topConfidence() const {
  cv::Mat channel;
  cv::extractChannel(class_probability, channel, 1);
  return channel;
}

int confusableClass(int k) {
  // road sidewalk building wall fence pole light sign vegetation terrain sky person rider car truck bus train moto bicycle
  static const int kPartner[19] = {1, 0, 3, 2, 3, 7, 5, 5, 9, 8, 2, 12, 11, 14, 15, 14, 15, 18, 17};
  return k >= 0 && k < 19 ? kPartner[k] : k;
}

SemanticNetworkOutput exactSemanticChannels(const cv::Mat& class_id, const cv::Mat& clean_gray) {
  CV_Assert(class_id.type() == CV_8UC1 && clean_gray.type() == CV_8UC1 && class_id.size() == clean_gray.size());
  const int width = class_id.cols, height = class_id.rows;
  SemanticNetworkOutput out;
  out.edge_strength = cv::Mat::zeros(height, width, CV_8UC1);
  out.edge_classes = cv::Mat::zeros(height, width, CV_32SC1);
  out.class_probability.create(height, width, CV_8UC4);

  cv::Mat gx, gy;
  cv::Sobel(clean_gray, gx, CV_16S, 1, 0, 3);
  cv::Sobel(clean_gray, gy, CV_16S, 0, 1, 3);
  for (int y = 0; y < height; ++y) {
    const std::uint8_t* row = class_id.ptr<std::uint8_t>(y);
    const std::uint8_t* above = class_id.ptr<std::uint8_t>(std::max(0, y - 1));
    const std::uint8_t* below = class_id.ptr<std::uint8_t>(std::min(height - 1, y + 1));
    const auto* sx = gx.ptr<std::int16_t>(y);
    const auto* sy = gy.ptr<std::int16_t>(y);
    auto* strength = out.edge_strength.ptr<std::uint8_t>(y);
    auto* classes = out.edge_classes.ptr<std::int32_t>(y);
    auto* probability = out.class_probability.ptr<cv::Vec4b>(y);
    for (int x = 0; x < width; ++x) {
      const int own = row[x];
      const int neighbours[4] = {row[std::max(0, x - 1)], row[std::min(width - 1, x + 1)], above[x], below[x]};
      std::uint32_t mask = 0;
      int other = -1;
      for (int n : neighbours)
        if (n != own) {
          mask |= 1u << n;
          other = n;
        }
      if (other >= 0) {
        mask |= 1u << own;
        strength[x] = 255;
        probability[x] = cv::Vec4b(static_cast<std::uint8_t>(own), 153, static_cast<std::uint8_t>(other), 102);
      } else {
        const int gradient = std::abs(sx[x]) + std::abs(sy[x]);
        if (gradient > kTextureLow) {
          const float p = kTextureMax * std::min(1.0f, static_cast<float>(gradient - kTextureLow) / (kTextureHigh - kTextureLow));
          strength[x] = static_cast<std::uint8_t>(std::lround(255.0f * p));
          mask = 1u << own;
        }
        probability[x] = cv::Vec4b(static_cast<std::uint8_t>(own), 242, static_cast<std::uint8_t>(confusableClass(own)), 8);
      }
      classes[x] = static_cast<std::int32_t>(mask);
    }
  }
  return out;
}

}  // namespace synthetic
}  // namespace semantic_edge_vo
