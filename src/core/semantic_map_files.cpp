#include "semantic_edge_vo/semantic_map_files.h"

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

std::string readEdgeBitmaskPng(const std::string& path, cv::Mat* bitmask) {
  cv::Mat image;
  if (std::string error = read8Bit(path, &image); !error.empty()) return error;
  if (image.channels() != 4) return channelError(path, image.channels(), "4 channels (class bits 0-23, edge strength)");
  *bitmask = image;
  return "";
}

}  // namespace semantic_edge_vo
