#include "semantic_edge_vo/edges/class_evidence.h"

#include <algorithm>
#include <array>
#include <sstream>

#include <opencv2/core.hpp>
#include <opencv2/core/hal/intrin.hpp>

#include "semantic_edge_vo/common/class_table.h"

namespace semantic_edge_vo {
namespace {

constexpr int kBitmaskClasses = 24;

std::size_t countInvalid(const cv::Mat& values) {
  std::size_t invalid = 0;
  const int n = values.cols * values.channels();
  for (int y = 0; y < values.rows; ++y) {
    const float* row = values.ptr<float>(y);
    for (int i = 0; i < n; ++i) invalid += !(row[i] >= 0.0f && row[i] <= 1.0f);  // NaN fails both
  }
  return invalid;
}

/// Whether any of the floats seen is NaN or outside [0, 1], from their minimum and maximum (-0
/// passes) and a NaN flag: four single-cycle operations per four values, no long dependency chains,
/// so the check runs at memory speed.
class RangeCheck {
 public:
  void add(const cv::v_float32x4& v) {
    low_ = cv::v_min(low_, v);
    high_ = cv::v_max(high_, v);
    nan_ = nan_ | (v != v);
  }
  void add(const float* values, int n) {
    int i = 0;
    for (; i + 4 <= n; i += 4) add(cv::v_load(values + i));
    for (; i < n; ++i) bad_tail_ |= !(values[i] >= 0.0f && values[i] <= 1.0f);
  }
  /// Byte values are always valid.
  void add(const cv::v_uint8x16&) {}
  bool bad() const {
    return bad_tail_ || cv::v_check_any(nan_) || cv::v_reduce_min(low_) < 0.0f || cv::v_reduce_max(high_) > 1.0f;
  }

 private:
  cv::v_float32x4 low_ = cv::v_setzero_f32(), high_ = cv::v_setzero_f32(), nan_ = cv::v_setzero_f32();
  bool bad_tail_ = false;
};

/// Maximum over the C channels of each of `cols` pixels, times `scale`, a register of channels at a
/// time (the last register overlaps the one before when C is not a multiple of its lanes; fewer
/// channels than lanes are padded with 0, which neither a valid maximum nor the check minds).
/// Every value also goes to `check`, while it is in a register.
template <typename T>
void channelMaximumRow(const T* in, int cols, int c, float scale, float* out, RangeCheck* check) {
  using Vector = decltype(cv::v_load(in));
  constexpr int kLanes = Vector::nlanes;
  for (int x = 0; x < cols; ++x, in += c) {
    Vector top;
    if (c < kLanes) {
      T padded[kLanes] = {};
      std::copy(in, in + c, padded);
      top = cv::v_load(padded);
    } else {
      top = cv::v_load(in + c - kLanes);
    }
    check->add(top);
    for (int k = 0; k + kLanes < c; k += kLanes) {
      const Vector v = cv::v_load(in + k);
      check->add(v);
      top = cv::v_max(top, v);
    }
    out[x] = static_cast<float>(cv::v_reduce_max(top)) * scale;
  }
}

inline cv::v_float32x4 broadcast(float value) { return cv::v_setall_f32(value); }
inline cv::v_uint8x16 broadcast(std::uint8_t value) { return cv::v_setall_u8(value); }

/// The C values of each of three pixels.
template <typename T>
using Triple = std::array<const T*, 3>;

/// Where the values of each pixel start.
template <typename T>
Triple<T> valuesAt(const cv::Mat& values, const PixelTriple& pixels) {
  Triple<T> in;
  for (std::size_t i = 0; i < pixels.size(); ++i) in[i] = values.ptr<T>(pixels[i].y) + pixels[i].x * values.channels();
  return in;
}

/// Class mask of the per-class maximum of C values over three pixels: the most probable class (the
/// first one on ties) plus every class reaching `threshold`; 0 when all are 0.
template <typename T>
std::uint32_t classMaskScalar(const Triple<T>& in, int c, T threshold, T* best) {
  std::uint32_t mask = 0;
  int top_class = 0;
  T top = 0;
  for (int k = 0; k < c; ++k) {
    T m = 0;
    for (const T* pixel : in) m = std::max(m, pixel[k]);
    if (m > top) {
      top = m;
      top_class = k;
    }
    if (m >= threshold) mask |= 1u << k;
  }
  *best = top;
  return top > 0 ? mask | 1u << top_class : 0u;
}

/// classMaskScalar() a register of classes at a time (the last register overlaps the one before
/// when C is not a multiple of its lanes; maxima and mask bits come out the same twice).
template <typename T>
std::uint32_t classMask(const Triple<T>& in, int c, T threshold, T* best) {
  using Vector = decltype(cv::v_load(in[0]));
  constexpr int kLanes = Vector::nlanes;
  if (c < kLanes) return classMaskScalar(in, c, threshold, best);
  T maximum[ClassTable::kMaxClasses];
  std::uint32_t mask = 0;
  Vector top = broadcast(T(0));
  for (int k = 0; k < c; k += kLanes) {
    const int at = std::min(k, c - kLanes);
    const Vector m = cv::v_max(cv::v_load(in[0] + at), cv::v_max(cv::v_load(in[1] + at), cv::v_load(in[2] + at)));
    cv::v_store(maximum + at, m);
    top = cv::v_max(top, m);
    mask |= static_cast<std::uint32_t>(cv::v_signmask(m >= broadcast(threshold))) << at;
  }
  *best = cv::v_reduce_max(top);
  if (!(*best > 0)) return 0u;
  return mask | 1u << (std::find(maximum, maximum + c, *best) - maximum);
}

/// The smallest byte whose probability (byte / 255 in float, as everywhere) reaches `threshold`.
std::uint8_t byteThreshold(float threshold) {
  int b = std::clamp(static_cast<int>(threshold * 255.0f), 0, 255);
  while (b > 0 && static_cast<float>(b - 1) * (1.0f / 255.0f) >= threshold) --b;
  while (b < 255 && static_cast<float>(b) * (1.0f / 255.0f) < threshold) ++b;
  return static_cast<std::uint8_t>(b);
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
  return invalidInRows(0, values.rows) ? countInvalid(values) : 0;
}

bool ClassEvidence::invalidInRows(int begin, int end) const {
  if (values.depth() != CV_32F) return false;
  RangeCheck check;
  for (int y = begin; y < end; ++y) check.add(values.ptr<float>(y), values.cols * values.channels());
  return check.bad();
}

std::uint32_t ClassEvidence::classMaskAcross(const PixelTriple& pixels, float threshold, float* best) const {
  CV_DbgAssert(classes <= ClassTable::kMaxClasses);
  switch (form) {
    case ClassEvidenceForm::kProbabilities: {
      if (values.depth() == CV_32F) return classMask(valuesAt<float>(values, pixels), classes, threshold, best);
      // Compared as bytes: / 255 keeps their order, so only the threshold and the result convert.
      std::uint8_t top = 0;
      const std::uint32_t mask = classMask(valuesAt<std::uint8_t>(values, pixels), classes, byteThreshold(threshold), &top);
      *best = top * (1.0f / 255.0f);
      return mask;
    }
    case ClassEvidenceForm::kLabels: {
      // At most three labelled classes, the others are 0: their maxima directly, the lowest class
      // winning ties as in a scan over classes.
      std::uint32_t mask = 0;
      int top_class = classes;
      *best = 0.0f;
      for (const std::uint8_t* in : valuesAt<std::uint8_t>(values, pixels)) {
        if (in[0] >= classes) continue;
        const float value = values.channels() == 2 ? in[1] * (1.0f / 255.0f) : 1.0f;
        if (value >= threshold) mask |= 1u << in[0];
        if (value > *best || (value == *best && in[0] < top_class)) {
          *best = value;
          top_class = in[0];
        }
      }
      return *best > 0.0f ? mask | 1u << top_class : 0u;
    }
    case ClassEvidenceForm::kBitmask: {
      std::uint32_t bits = 0;  // values are 0 or 1: their maximum is the union of the bits
      for (const std::uint8_t* in : valuesAt<std::uint8_t>(values, pixels)) bits |= in[0] | (in[1] << 8) | (in[2] << 16);
      bits &= (1u << classes) - 1u;
      *best = bits ? 1.0f : 0.0f;
      return bits;  // every set class reaches any threshold <= 1
    }
  }
  return 0u;
}

void ClassEvidence::prefetch(const PixelTriple& pixels) const {
  constexpr std::size_t kCacheLine = 64;
  const std::size_t size = values.elemSize();
  for (const cv::Point& p : pixels) {
    const std::uint8_t* first = values.ptr<std::uint8_t>(p.y) + p.x * size;
    for (std::size_t offset = 0; offset < size; offset += kCacheLine) __builtin_prefetch(first + offset);
    __builtin_prefetch(first + size - 1);  // the last line, when the values straddle one more
  }
}

cv::Mat ClassEvidence::edgeProbability(std::size_t* invalid) const {
  cv::Mat maximum(values.size(), CV_32FC1);
  if (invalid) *invalid = 0;
  if (form == ClassEvidenceForm::kBitmask) {
    cv::Mat strength;
    cv::extractChannel(values, strength, 3);
    strength.convertTo(maximum, CV_32F, 1.0 / 255.0);
    return maximum;
  }
  RangeCheck check;  // of float values, in the same pass
  for (int y = 0; y < values.rows; ++y) {
    float* out = maximum.ptr<float>(y);
    if (values.depth() == CV_8U) channelMaximumRow(values.ptr<std::uint8_t>(y), values.cols, values.channels(), 1.0f / 255.0f, out, &check);
    else channelMaximumRow(values.ptr<float>(y), values.cols, values.channels(), 1.0f, out, &check);
  }
  if (check.bad() && invalid) *invalid = countInvalid(values);
  return maximum;
}

}  // namespace semantic_edge_vo
