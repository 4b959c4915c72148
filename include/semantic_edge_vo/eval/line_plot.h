#pragma once
#include <array>
#include <string>
#include <vector>

#include <opencv2/core/mat.hpp>

namespace semantic_edge_vo {

struct PlotSeries {
  std::string label;
  std::vector<double> x, y;
  std::array<int, 3> bgr{{200, 80, 30}};
};

struct LinePlotOptions {
  int width_px = 900, height_px = 600;
  std::string title, x_label, y_label;
  bool y_from_zero = true;  ///< the y axis starts at 0 (rates, errors)
};

/// A line plot with markers: axes with ticks at round values, grid, labels, legend, title.
/// Returns an 8-bit BGR image (write it with cv::imwrite).
cv::Mat renderLinePlot(const std::vector<PlotSeries>& series, const LinePlotOptions& options);

/// A tick value printed with as many decimals as the tick step needs ("0", not "-0").
std::string tickLabel(double value, double step);

/// Round tick values covering [low, high]: steps of 1, 2 or 5 times a power of ten, about `count` of them.
std::vector<double> niceTicks(double low, double high, int count = 6);

}  // namespace semantic_edge_vo
