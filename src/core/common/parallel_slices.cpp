#include "semantic_edge_vo/common/parallel_slices.h"

#include <opencv2/core/utility.hpp>

namespace semantic_edge_vo {

void forEachSlice(const std::function<void(int slice)>& work) {
  cv::parallel_for_(cv::Range(0, kParallelSlices), [&](const cv::Range& range) {
    for (int slice = range.start; slice < range.end; ++slice) work(slice);
  }, kParallelSlices);
}

void forEachIndex(std::size_t count, const std::function<void(std::size_t i)>& work) {
  forEachSlice([&](int slice) {
    const auto [begin, end] = sliceRange(count, slice);
    for (std::size_t i = begin; i < end; ++i) work(i);
  });
}

}  // namespace semantic_edge_vo
