#pragma once
// Deterministic use of both cores: work is split into a fixed number of slices (not one per thread),
// so partial results added in slice order are the same on every machine and every run.
#include <cstddef>
#include <functional>
#include <utility>

namespace semantic_edge_vo {

constexpr int kParallelSlices = 8;

/// [begin, end) of slice `slice` of `count` items.
inline std::pair<std::size_t, std::size_t> sliceRange(std::size_t count, int slice) {
  return {count * static_cast<std::size_t>(slice) / kParallelSlices, count * static_cast<std::size_t>(slice + 1) / kParallelSlices};
}

/// Calls work(slice) for every slice on OpenCV's thread pool and returns when all are done. Slices
/// must write only their own results.
void forEachSlice(const std::function<void(int slice)>& work);

/// Calls work(i) for every i in [0, count), sliced as above.
void forEachIndex(std::size_t count, const std::function<void(std::size_t i)>& work);

}  // namespace semantic_edge_vo
