#include "semantic_edge_vo/eval/line_plot.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>

#include <opencv2/imgproc.hpp>

namespace semantic_edge_vo {
std::string tickLabel(double value, double step) {
  const int decimals = std::max(0, static_cast<int>(-std::floor(std::log10(step) + 1e-9)));
  std::ostringstream label;
  label << std::fixed << std::setprecision(decimals) << (std::abs(value) < 1e-6 * step ? 0.0 : value);
  return label.str();
}

std::vector<double> niceTicks(double low, double high, int count) {
  if (!(high > low)) high = low + 1.0;
  const double raw = (high - low) / std::max(1, count);
  const double power = std::pow(10.0, std::floor(std::log10(raw)));
  double step = power;
  for (double factor : {1.0, 2.0, 5.0, 10.0}) {
    step = factor * power;
    if (step >= raw) break;
  }
  std::vector<double> ticks;
  for (double t = std::floor(low / step) * step; t <= high + 1e-9 * step; t += step) ticks.push_back(t);
  if (ticks.back() < high - 1e-9 * step) ticks.push_back(ticks.back() + step);
  return ticks;
}

cv::Mat renderLinePlot(const std::vector<PlotSeries>& series, const LinePlotOptions& options) {
  cv::Mat image(options.height_px, options.width_px, CV_8UC3, cv::Scalar(255, 255, 255));
  double x_min = std::numeric_limits<double>::max(), x_max = std::numeric_limits<double>::lowest();
  double y_min = options.y_from_zero ? 0.0 : std::numeric_limits<double>::max(), y_max = std::numeric_limits<double>::lowest();
  for (const PlotSeries& s : series) {
    for (double x : s.x) x_min = std::min(x_min, x), x_max = std::max(x_max, x);
    for (double y : s.y) y_min = std::min(y_min, y), y_max = std::max(y_max, y);
  }
  if (x_max < x_min) x_min = 0.0, x_max = 1.0;
  if (y_max < y_min) y_min = 0.0, y_max = 1.0;
  const std::vector<double> x_ticks = niceTicks(x_min, x_max), y_ticks = niceTicks(y_min, y_max);
  x_min = x_ticks.front(), x_max = x_ticks.back(), y_min = y_ticks.front(), y_max = y_ticks.back();

  const cv::Rect area(80, 50, options.width_px - 110, options.height_px - 120);
  const auto toPixel = [&](double x, double y) {
    return cv::Point(static_cast<int>(area.x + (x - x_min) / (x_max - x_min) * area.width),
                     static_cast<int>(area.br().y - (y - y_min) / (y_max - y_min) * area.height));
  };
  const cv::Scalar black(0, 0, 0), grid(225, 225, 225);
  const int font = cv::FONT_HERSHEY_SIMPLEX;
  for (double t : x_ticks) {
    const cv::Point p = toPixel(t, y_min);
    cv::line(image, cv::Point(p.x, area.y), p, grid, 1);
    cv::line(image, p, p + cv::Point(0, 5), black, 1);
    const std::string label = tickLabel(t, x_ticks[1] - x_ticks[0]);
    cv::putText(image, label, p + cv::Point(-4 * static_cast<int>(label.size()), 22), font, 0.45, black, 1, cv::LINE_AA);
  }
  for (double t : y_ticks) {
    const cv::Point p = toPixel(x_min, t);
    cv::line(image, p, cv::Point(area.br().x, p.y), grid, 1);
    cv::line(image, p, p - cv::Point(5, 0), black, 1);
    const std::string label = tickLabel(t, y_ticks[1] - y_ticks[0]);
    cv::putText(image, label, p + cv::Point(-12 - 9 * static_cast<int>(label.size()), 5), font, 0.45, black, 1, cv::LINE_AA);
  }
  cv::rectangle(image, area, black, 1);
  cv::putText(image, options.title, cv::Point(area.x, 30), font, 0.65, black, 1, cv::LINE_AA);
  cv::putText(image, options.x_label, cv::Point(area.x + area.width / 2 - 4 * static_cast<int>(options.x_label.size()),
                                                options.height_px - 25), font, 0.5, black, 1, cv::LINE_AA);
  cv::Mat y_label(24, area.height, CV_8UC3, cv::Scalar(255, 255, 255));
  cv::putText(y_label, options.y_label, cv::Point(area.height / 2 - 4 * static_cast<int>(options.y_label.size()), 17), font,
              0.5, black, 1, cv::LINE_AA);
  cv::rotate(y_label, y_label, cv::ROTATE_90_COUNTERCLOCKWISE);
  y_label.copyTo(image(cv::Rect(8, area.y, y_label.cols, y_label.rows)));

  for (std::size_t k = 0; k < series.size(); ++k) {
    const PlotSeries& s = series[k];
    const cv::Scalar colour(s.bgr[0], s.bgr[1], s.bgr[2]);
    const std::size_t n = std::min(s.x.size(), s.y.size());
    for (std::size_t i = 0; i < n; ++i) {
      if (i > 0) cv::line(image, toPixel(s.x[i - 1], s.y[i - 1]), toPixel(s.x[i], s.y[i]), colour, 2, cv::LINE_AA);
      cv::circle(image, toPixel(s.x[i], s.y[i]), 4, colour, cv::FILLED, cv::LINE_AA);
    }
    const cv::Point legend(area.br().x - 170, area.y + 22 + 22 * static_cast<int>(k));
    cv::line(image, legend, legend + cv::Point(30, 0), colour, 3, cv::LINE_AA);
    cv::putText(image, s.label, legend + cv::Point(38, 5), font, 0.5, black, 1, cv::LINE_AA);
  }
  return image;
}

}  // namespace semantic_edge_vo
