#include "semantic_edge_vo/ros/class_input.h"

#include <boost/make_shared.hpp>
#include <opencv2/imgcodecs.hpp>
#include <sensor_msgs/image_encodings.h>

namespace semantic_edge_vo {
namespace enc = sensor_msgs::image_encodings;
namespace {

/// OpenCV type of an encoding; -1 when not a plain 8-bit or 32-bit float layout.
int matType(const std::string& encoding) {
  try {
    const int depth = enc::bitDepth(encoding), channels = enc::numChannels(encoding);
    if (channels < 1 || channels > CV_CN_MAX) return -1;
    if (depth == 8 && !enc::isColor(encoding) && !enc::isBayer(encoding)) return CV_8UC(channels);
    if (depth == 32 && encoding.rfind("32FC", 0) == 0) return CV_32FC(channels);
  } catch (const std::exception&) {
  }
  return -1;
}

/// Header on the message buffer; empty when the step and data do not hold the image.
cv::Mat wrap(const sensor_msgs::Image& msg, int type, std::string* reason, std::string* detail) {
  const std::size_t row_bytes = static_cast<std::size_t>(msg.width) * CV_ELEM_SIZE(type);
  if (msg.width == 0 || msg.height == 0 || msg.step < row_bytes ||
      msg.data.size() < static_cast<std::size_t>(msg.step) * msg.height || msg.is_bigendian) {
    *reason = "malformed_image";
    *detail = "step " + std::to_string(msg.step) + " and " + std::to_string(msg.data.size()) + " bytes do not hold a " +
              std::to_string(msg.width) + "x" + std::to_string(msg.height) + " " + msg.encoding + " little-endian image";
    return {};
  }
  return cv::Mat(static_cast<int>(msg.height), static_cast<int>(msg.width), type,
                 const_cast<std::uint8_t*>(msg.data.data()), msg.step);
}

}  // namespace

std::string classEvidenceFromImage(const sensor_msgs::Image& msg, ClassEvidenceForm form, int classes,
                                   ClassEvidence* evidence, std::string* detail) {
  const int type = matType(msg.encoding);
  const int depth = CV_MAT_DEPTH(type), channels = CV_MAT_CN(type);
  bool fits = type >= 0;
  const char* expected = "32FC<C> or 8UC<C>";
  if (form == ClassEvidenceForm::kLabels) {
    fits = fits && depth == CV_8U && channels <= 2;
    expected = "8UC1, mono8 or 8UC2";
  } else if (form == ClassEvidenceForm::kBitmask) {
    fits = fits && depth == CV_8U && channels == 4;
    expected = "8UC4";
  }
  if (!fits) {
    *detail = "encoding '" + msg.encoding + "' for the " + toString(form) + " class form (expected " + expected + ")";
    return "unsupported_encoding";
  }
  std::string reason;
  evidence->form = form;
  evidence->classes = classes;
  evidence->values = wrap(msg, type, &reason, detail);
  return reason;
}

std::string edgeProbabilityFromImage(const sensor_msgs::Image& msg, cv::Mat* probability, std::string* detail) {
  const int type = matType(msg.encoding);
  if (type != CV_8UC1 && type != CV_32FC1) {
    *detail = "edge probability encoding '" + msg.encoding + "' (expected 32FC1, 8UC1 or mono8)";
    return "unsupported_encoding";
  }
  std::string reason;
  *probability = wrap(msg, type, &reason, detail);
  return reason;
}

std::string decodeCompressedImage(const sensor_msgs::CompressedImage& msg, sensor_msgs::ImagePtr* image, std::string* detail) {
  cv::Mat decoded;
  try {
    decoded = cv::imdecode(msg.data, cv::IMREAD_UNCHANGED);
  } catch (const cv::Exception& e) {
    *detail = e.what();
    return "decode_failed";
  }
  if (decoded.empty() || decoded.depth() != CV_8U || (decoded.channels() != 1 && decoded.channels() != 3)) {
    *detail = "format '" + msg.format + "', " + std::to_string(msg.data.size()) + " bytes: not an 8-bit gray or colour image";
    return "decode_failed";
  }
  auto out = boost::make_shared<sensor_msgs::Image>();
  out->header = msg.header;
  out->width = static_cast<std::uint32_t>(decoded.cols);
  out->height = static_cast<std::uint32_t>(decoded.rows);
  out->encoding = decoded.channels() == 1 ? enc::MONO8 : enc::BGR8;
  out->step = static_cast<std::uint32_t>(decoded.cols * decoded.channels());
  out->data.resize(static_cast<std::size_t>(out->step) * out->height);
  decoded.copyTo(cv::Mat(decoded.rows, decoded.cols, decoded.type(), out->data.data()));
  *image = out;
  return {};
}

}  // namespace semantic_edge_vo
