#include "semantic_edge_vo/class_evidence.h"

#include <algorithm>
#include <cstring>
#include <sstream>

#include <opencv2/core.hpp>
#include <opencv2/core/hal/intrin.hpp>

namespace semantic_edge_vo {
namespace {

constexpr int kBitmaskClasses = 24;

/// Bits of a float outside [0, 1] or NaN: positive floats order like their bit patterns, so anything
/// above the bits of 1.0f is too large or NaN, and every negative pattern but -0 is below zero.
constexpr std::uint32_t kOneBits = 0x3f800000u, kNegativeZeroBits = 0x80000000u;

inline bool invalidBits(std::uint32_t bits) { return bits > kOneBits && bits != kNegativeZeroBits; }

std::size_t countInvalid(const cv::Mat& values) {
  std::size_t invalid = 0;
  const int n = values.cols * values.channels();
  for (int y = 0; y < values.rows; ++y) {
    const float* row = values.ptr<float>(y);
    for (int i = 0; i < n; ++i) invalid += !(row[i] >= 0.0f && row[i] <= 1.0f);  // NaN fails both
  }
  return invalid;
}

/// Whether any float is NaN or outside [0, 1], four at a time.
bool anyInvalid(const cv::Mat& values) {
  const cv::v_uint32x4 one = cv::v_setall_u32(kOneBits), negative_zero = cv::v_setall_u32(kNegativeZeroBits);
  cv::v_uint32x4 bad = cv::v_setzero_u32();
  std::uint32_t bad_tail = 0;
  const int n = values.cols * values.channels();
  for (int y = 0; y < values.rows; ++y) {
    const std::uint32_t* row = values.ptr<std::uint32_t>(y);
    int i = 0;
    for (; i + 4 <= n; i += 4) {
      const cv::v_uint32x4 bits = cv::v_load(row + i);
      bad = bad | ((bits > one) & (bits != negative_zero));
    }
    for (; i < n; ++i) bad_tail |= invalidBits(row[i]);
  }
  return cv::v_check_any(bad) || bad_tail;
}

/// Per-pixel maximum over the 32-bit float channels, four channels at a time; true when a value is
/// NaN or outside [0, 1] (checked in the same pass).
bool channelMaximumFloat(const cv::Mat& values, cv::Mat* maximum) {
  const int c = values.channels();
  const cv::v_uint32x4 one = cv::v_setall_u32(kOneBits), negative_zero = cv::v_setall_u32(kNegativeZeroBits);
  cv::v_uint32x4 bad = cv::v_setzero_u32();
  std::uint32_t bad_tail = 0;
  for (int y = 0; y < values.rows; ++y) {
    const float* in = values.ptr<float>(y);
    float* out = maximum->ptr<float>(y);
    for (int x = 0; x < values.cols; ++x, in += c) {
      cv::v_float32x4 top = cv::v_setall_f32(0.0f);
      int k = 0;
      for (; k + 4 <= c; k += 4) {
        const cv::v_float32x4 v = cv::v_load(in + k);
        top = cv::v_max(top, v);
        const cv::v_uint32x4 bits = cv::v_reinterpret_as_u32(v);
        bad = bad | ((bits > one) & (bits != negative_zero));
      }
      float m = cv::v_reduce_max(top);
      for (; k < c; ++k) {
        m = std::max(m, in[k]);
        std::uint32_t bits;
        std::memcpy(&bits, in + k, sizeof(bits));
        bad_tail |= invalidBits(bits);
      }
      out[x] = m;
    }
  }
  return cv::v_check_any(bad) || bad_tail;
}

/// Per-pixel maximum over the 8-bit channels (16 at a time), / 255.
void channelMaximumByte(const cv::Mat& values, cv::Mat* maximum) {
  const int c = values.channels();
  for (int y = 0; y < values.rows; ++y) {
    const std::uint8_t* in = values.ptr<std::uint8_t>(y);
    float* out = maximum->ptr<float>(y);
    for (int x = 0; x < values.cols; ++x, in += c) {
      int k = 0;
      std::uint8_t m = 0;
      if (c >= 16) {
        m = cv::v_reduce_max(cv::v_load(in));
        k = 16;
      }
      for (; k < c; ++k) m = std::max(m, in[k]);
      out[x] = m * (1.0f / 255.0f);
    }
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
  if (values.depth() != CV_32F || !anyInvalid(values)) return 0;
  return countInvalid(values);
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

cv::Mat ClassEvidence::edgeProbability(std::size_t* invalid) const {
  cv::Mat maximum(values.size(), CV_32FC1);
  if (invalid) *invalid = 0;
  if (form == ClassEvidenceForm::kBitmask) {
    cv::Mat strength;
    cv::extractChannel(values, strength, 3);
    strength.convertTo(maximum, CV_32F, 1.0 / 255.0);
  } else if (values.depth() == CV_32F) {
    if (channelMaximumFloat(values, &maximum) && invalid) *invalid = countInvalid(values);
  } else {
    channelMaximumByte(values, &maximum);
  }
  return maximum;
}

}  // namespace semantic_edge_vo
