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
  cv::Mat image;
  if (std::string error = read8Bit(path, &image); !error.empty()) return error;
  if (image.channels() == 1) {
    *labels = image;
  } else if (image.channels() == 4) {
    cv::Mat pair(image.size(), CV_8UC2);
    const int from_to[] = {0, 0, 1, 1};
    cv::mixChannels(&image, 1, &pair, 1, from_to, 2);
    *labels = pair;
  } else {
    return channelError(path, image.channels(),
                        "1 channel (class index) or 4 (class index, confidence x 255, ...): a colour-coded "
                        "segmentation is not a label map");
  }
  return "";
}

std::string writeClassLabelsPng(const std::string& path, const cv::Mat& probabilities) {
  const int classes = probabilities.channels();
  if (probabilities.depth() != CV_8U || classes < 1 || classes > 255)
    return path + ": expected 8-bit probabilities of 1 to 255 classes, got depth " + std::to_string(probabilities.depth()) + " and " +
           std::to_string(classes) + " channel(s)";
  cv::Mat top_two(probabilities.size(), CV_8UC4);
  for (int y = 0; y < probabilities.rows; ++y) {
    const std::uint8_t* p = probabilities.ptr<std::uint8_t>(y);
    auto* out = top_two.ptr<cv::Vec4b>(y);
    for (int x = 0; x < probabilities.cols; ++x, p += classes) {
      int first = 0, second = classes > 1 ? 1 : 0;
      if (classes > 1 && p[1] > p[0]) std::swap(first, second);
      for (int c = 2; c < classes; ++c) {
        if (p[c] > p[first]) {
          second = first;
          first = c;
        } else if (p[c] > p[second]) {
          second = c;
        }
      }
      out[x] = cv::Vec4b(static_cast<std::uint8_t>(first), p[first], static_cast<std::uint8_t>(second), classes > 1 ? p[second] : 0);
    }
  }
  try {
    if (!cv::imwrite(path, top_two)) return path + ": could not be written";
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
