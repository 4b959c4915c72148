#include "semantic_edge_vo/class_evidence.h"

#include <algorithm>
#include <cstring>
#include <sstream>

#include <opencv2/core.hpp>

namespace semantic_edge_vo {
namespace {

constexpr int kBitmaskClasses = 24;

/// Per-pixel maximum over the channels of an interleaved C-channel image, as float (scale applied).
template <typename T>
void channelMaximum(const cv::Mat& values, float scale, cv::Mat* maximum) {
  const int c = values.channels();
  for (int y = 0; y < values.rows; ++y) {
    const T* in = values.ptr<T>(y);
    float* out = maximum->ptr<float>(y);
    for (int x = 0; x < values.cols; ++x, in += c) out[x] = static_cast<float>(*std::max_element(in, in + c)) * scale;
  }
}

}  // namespace

bool parseClassEvidenceForm(const std::string& text, ClassEvidenceForm* form) {
  if (text == "probabilities") *form = ClassEvidenceForm::kProbabilities;
  else if (text == "labels") *form = ClassEvidenceForm::kLabels;
  else if (text == "bitmask") *form = ClassEvidenceForm::kBitmask;
  else return false;
  return true;
}

const char* toString(ClassEvidenceForm form) {
  switch (form) {
    case ClassEvidenceForm::kProbabilities: return "probabilities";
    case ClassEvidenceForm::kLabels: return "labels";
    case ClassEvidenceForm::kBitmask: return "bitmask";
  }
  return "?";
}

std::string ClassEvidence::checkLayout(cv::Size image_size, std::string* detail) const {
  std::ostringstream text;
  const int depth = values.depth(), channels = values.channels();
  switch (form) {
    case ClassEvidenceForm::kProbabilities:
      if (depth != CV_32F && depth != CV_8U) {
        *detail = "class probabilities must be 32-bit float or 8-bit per channel";
        return "unsupported_layout";
      }
      if (channels != classes) {
        text << "class map has " << channels << " channels, the class table has " << classes << " classes";
        *detail = text.str();
        return "channel_count_mismatch";
      }
      break;
    case ClassEvidenceForm::kLabels:
      if (depth != CV_8U || channels > 2) {
        *detail = "class labels must be 8-bit with 1 channel (index) or 2 (index, confidence x 255)";
        return "unsupported_layout";
      }
      break;
    case ClassEvidenceForm::kBitmask:
      if (depth != CV_8U || channels != 4) {
        *detail = "class bitmask must be 8-bit with 4 channels (3 bytes of class bits, strength x 255)";
        return "unsupported_layout";
      }
      if (classes > kBitmaskClasses) {
        text << "the bitmask form holds " << kBitmaskClasses << " classes, the class table has " << classes;
        *detail = text.str();
        return "channel_count_mismatch";
      }
      break;
  }
  if (values.size() != image_size) {
    text << "class map is " << values.cols << "x" << values.rows << ", image is " << image_size.width << "x"
         << image_size.height;
    *detail = text.str();
    return "size_mismatch";
  }
  return {};
}

std::size_t ClassEvidence::invalidValueCount() const {
  if (values.depth() != CV_32F) return 0;
  std::size_t invalid = 0;
  const int n = values.cols * values.channels();
  for (int y = 0; y < values.rows; ++y) {
    const float* row = values.ptr<float>(y);
    for (int i = 0; i < n; ++i) invalid += !(row[i] >= 0.0f && row[i] <= 1.0f);  // NaN fails both
  }
  return invalid;
}

void ClassEvidence::probabilitiesAt(int x, int y, float* out) const {
  switch (form) {
    case ClassEvidenceForm::kProbabilities:
      if (values.depth() == CV_32F) {
        std::memcpy(out, values.ptr<float>(y) + x * classes, sizeof(float) * static_cast<std::size_t>(classes));
      } else {
        const std::uint8_t* in = values.ptr<std::uint8_t>(y) + x * classes;
        for (int c = 0; c < classes; ++c) out[c] = in[c] * (1.0f / 255.0f);
      }
      return;
    case ClassEvidenceForm::kLabels: {
      std::fill(out, out + classes, 0.0f);
      const std::uint8_t* in = values.ptr<std::uint8_t>(y) + x * values.channels();
      if (in[0] < classes) out[in[0]] = values.channels() == 2 ? in[1] * (1.0f / 255.0f) : 1.0f;
      return;
    }
    case ClassEvidenceForm::kBitmask: {
      const std::uint8_t* in = values.ptr<std::uint8_t>(y) + 4 * x;
      const std::uint32_t bits = in[0] | (in[1] << 8) | (in[2] << 16);
      for (int c = 0; c < classes; ++c) out[c] = (bits >> c) & 1u ? 1.0f : 0.0f;
      return;
    }
  }
}

cv::Mat ClassEvidence::edgeProbability() const {
  cv::Mat maximum(values.size(), CV_32FC1);
  if (form == ClassEvidenceForm::kBitmask) {
    cv::Mat strength;
    cv::extractChannel(values, strength, 3);
    strength.convertTo(maximum, CV_32F, 1.0 / 255.0);
  } else if (values.depth() == CV_32F) {
    channelMaximum<float>(values, 1.0f, &maximum);
  } else {
    channelMaximum<std::uint8_t>(values, 1.0f / 255.0f, &maximum);
  }
  return maximum;
}

}  // namespace semantic_edge_vo
