#pragma once
#include <algorithm>
#include <cmath>
#include <deque>
#include <vector>

namespace semantic_edge_vo {

/// Huber cost of a residual r with threshold k: r^2 / 2 inside, linear outside.
inline double huberCost(double r, double k) {
  const double a = std::abs(r);
  return a <= k ? 0.5 * r * r : k * (a - 0.5 * k);
}

/// Iteratively reweighted least-squares weight of a residual r under the Huber cost with threshold k.
inline double huberWeight(double r, double k) {
  const double a = std::abs(r);
  return a <= k ? 1.0 : k / a;
}

/// Median (the upper one for an even count) of the values, 0 for none. Takes a copy to reorder.
inline double median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  const auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), middle, values.end());
  return *middle;
}

/// Appends the value to the recent ones a statistic is taken over, keeping the newest `count`.
template <typename T>
void keepLast(const T& value, std::size_t count, std::deque<T>* values) {
  values->push_back(value);
  if (values->size() > count) values->pop_front();
}

}  // namespace semantic_edge_vo
