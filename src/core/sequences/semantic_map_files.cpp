#include "semantic_edge_vo/sequences/semantic_map_files.h"

#include <filesystem>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

namespace semantic_edge_vo {
namespace {

/// Reads `path` unchanged; "" or what is wrong (missing, unreadable, not 8-bit).
std::string read8Bit(const std::string& path, cv::Mat* image) {
  if (!std::filesystem::exists(path)) return path + ": no such file";
  *image = cv::imread(path, cv::IMREAD_UNCHANGED);
  if (image->empty()) return path + ": not a readable image";
  if (image->depth() != CV_8U) return path + ": expected 8 bits per channel, found " + std::to_string(8 * image->elemSize1());
  return "";
}

std::string channelError(const std::string& path, int channels, const char* expected) {
  return path + ": expected " + expected + ", found " + std::to_string(channels) + " channel(s)";
}

}  // namespace

std::string readClassLabelsPng(const std::string& path, cv::Mat* labels) {
  if (!std::filesystem::exists(path)) return path + ": no such file";
  const cv::Mat image = cv::imread(path, cv::IMREAD_UNCHANGED);
  if (image.empty()) return path + ": not a readable image";
  if (image.type() == CV_16UC1) {
    cv::Mat pair(image.size(), CV_8UC2);
    for (int y = 0; y < image.rows; ++y) {
      const std::uint16_t* in = image.ptr<std::uint16_t>(y);
      auto* out = pair.ptr<cv::Vec2b>(y);
      for (int x = 0; x < image.cols; ++x) out[x] = cv::Vec2b(static_cast<std::uint8_t>(in[x] & 0xff), static_cast<std::uint8_t>(in[x] >> 8));
    }
    *labels = pair;
    return "";
  }
  if (image.depth() != CV_8U) return path + ": expected 8 bits per channel, or one 16-bit channel, found " + std::to_string(8 * image.elemSize1()) + " bits";
  if (image.channels() == 1) {
    *labels = image;
  } else if (image.channels() == 4) {
    cv::Mat pair(image.size(), CV_8UC2);
    const int from_to[] = {0, 0, 1, 1};
    cv::mixChannels(&image, 1, &pair, 1, from_to, 2);
    *labels = pair;
  } else {
    return channelError(path, image.channels(),
                        "1 channel (class index; 16 bits: class + 256 x confidence x 255) or 4 (class index, confidence x 255, ...): "
                        "a colour-coded segmentation is not a label map");
  }
  return "";
}

std::string writeClassLabelsPng(const std::string& path, const cv::Mat& probabilities) {
  const int classes = probabilities.channels();
  if (probabilities.depth() != CV_8U || classes < 1 || classes > 255)
    return path + ": expected 8-bit probabilities of 1 to 255 classes, got depth " + std::to_string(probabilities.depth()) + " and " +
           std::to_string(classes) + " channel(s)";
  // One 16-bit value a pixel, class + 256 x confidence: half the bytes of the 4-channel layout, and
  // the quickest of them to read.
  cv::Mat packed(probabilities.size(), CV_16UC1);
  for (int y = 0; y < probabilities.rows; ++y) {
    const std::uint8_t* p = probabilities.ptr<std::uint8_t>(y);
    auto* out = packed.ptr<std::uint16_t>(y);
    for (int x = 0; x < probabilities.cols; ++x, p += classes) {
      int best = 0;
      for (int c = 1; c < classes; ++c)
        if (p[c] > p[best]) best = c;
      out[x] = static_cast<std::uint16_t>(best | p[best] << 8);
    }
  }
  try {
    if (!cv::imwrite(path, packed)) return path + ": could not be written";
  } catch (const cv::Exception& e) {
    return path + ": " + e.what();
  }
  return "";
}

std::string readEdgeBitmaskPng(const std::string& path, cv::Mat* bitmask) {
  cv::Mat image;
  if (std::string error = read8Bit(path, &image); !error.empty()) return error;
  if (image.channels() != 4) return channelError(path, image.channels(), "4 channels (class bits 0-23, edge strength)");
  *bitmask = image;
  return "";
}

}  // namespace semantic_edge_vo
