#pragma once
#include <cstddef>
#include <vector>

namespace semantic_edge_vo {

/// A read-only window on contiguous elements someone else owns (a std::vector of the core or of a
/// ROS message). Lets core algorithms run on message buffers without copying them.
template <typename T>
class ArrayView {
 public:
  ArrayView() = default;
  ArrayView(const T* data, std::size_t size) : data_(data), size_(size) {}
  ArrayView(const std::vector<T>& vector) : data_(vector.data()), size_(vector.size()) {}  // NOLINT

  const T& operator[](std::size_t i) const { return data_[i]; }
  const T* data() const { return data_; }
  std::size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }
  const T* begin() const { return data_; }
  const T* end() const { return data_ + size_; }

 private:
  const T* data_ = nullptr;
  std::size_t size_ = 0;
};

}  // namespace semantic_edge_vo
