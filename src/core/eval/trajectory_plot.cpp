#include "semantic_edge_vo/eval/trajectory_plot.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "semantic_edge_vo/eval/line_plot.h"

namespace semantic_edge_vo {
namespace {

constexpr int kFont = cv::FONT_HERSHEY_SIMPLEX;
constexpr double kFontScale = 0.5;
constexpr int kShift = 4;  ///< fixed-point bits for sub-pixel lines
const cv::Scalar kText(0, 0, 0), kGrid(228, 228, 228), kGroundTruth(40, 40, 40), kEstimate(20, 110, 235);

cv::Size textSize(const std::string& text) {
  int baseline = 0;
  return cv::getTextSize(text, kFont, kFontScale, 1, &baseline);
}

void putText(cv::Mat* image, const std::string& text, cv::Point origin) {
  cv::putText(*image, text, origin, kFont, kFontScale, kText, 1, cv::LINE_AA);
}

/// Maps (x, z) metres into the plot area, equal scale on both axes.
struct PlotFrame {
  cv::Rect area;
  double x0 = 0, z0 = 0;        ///< metres at the area's left and bottom edges
  double metres_per_px = 1.0;

  cv::Point pixel(double x, double z) const {  // fixed point with kShift bits
    const double u = area.x + (x - x0) / metres_per_px, v = area.y + area.height - (z - z0) / metres_per_px;
    return {cvRound(u * (1 << kShift)), cvRound(v * (1 << kShift))};
  }
};

PlotFrame fitFrame(const std::vector<Eigen::Vector3d>& gt, const std::vector<Eigen::Vector3d>& est, cv::Rect area) {
  double x_min = std::numeric_limits<double>::infinity(), x_max = -x_min, z_min = x_min, z_max = -x_min;
  for (const auto* points : {&gt, &est})
    for (const auto& p : *points) {
      x_min = std::min(x_min, p.x()), x_max = std::max(x_max, p.x());
      z_min = std::min(z_min, p.z()), z_max = std::max(z_max, p.z());
    }
  if (x_min > x_max) x_min = z_min = -0.5, x_max = z_max = 0.5;  // nothing to draw
  const double span_x = std::max(x_max - x_min, 1.0) * 1.06, span_z = std::max(z_max - z_min, 1.0) * 1.06;
  PlotFrame frame;
  frame.area = area;
  frame.metres_per_px = std::max(span_x / area.width, span_z / area.height);
  frame.x0 = 0.5 * (x_min + x_max) - 0.5 * frame.metres_per_px * area.width;
  frame.z0 = 0.5 * (z_min + z_max) - 0.5 * frame.metres_per_px * area.height;
  return frame;
}

void drawAxes(const PlotFrame& frame, cv::Mat* image) {
  const cv::Rect& area = frame.area;
  // One round step for both axes (equal aspect), about six ticks along the shorter one.
  const std::vector<double> ticks = niceTicks(0.0, frame.metres_per_px * std::min(area.width, area.height), 6);
  const double step = ticks[1] - ticks[0];
  const double x_end = frame.x0 + frame.metres_per_px * area.width, z_end = frame.z0 + frame.metres_per_px * area.height;
  for (double x = std::ceil(frame.x0 / step) * step; x <= x_end; x += step) {
    const int u = frame.pixel(x, frame.z0).x >> kShift;
    cv::line(*image, {u, area.y}, {u, area.y + area.height}, kGrid, 1);
    cv::line(*image, {u, area.y + area.height}, {u, area.y + area.height + 5}, kText, 1);
    const std::string label = tickLabel(x, step);
    putText(image, label, {u - textSize(label).width / 2, area.y + area.height + 22});
  }
  for (double z = std::ceil(frame.z0 / step) * step; z <= z_end; z += step) {
    const int v = frame.pixel(frame.x0, z).y >> kShift;
    cv::line(*image, {area.x, v}, {area.x + area.width, v}, kGrid, 1);
    cv::line(*image, {area.x - 5, v}, {area.x, v}, kText, 1);
    const std::string label = tickLabel(z, step);
    const cv::Size size = textSize(label);
    putText(image, label, {area.x - 9 - size.width, v + size.height / 2});
  }

  const std::string x_label = "x [m]";
  putText(image, x_label, {area.x + area.width / 2 - textSize(x_label).width / 2, area.y + area.height + 50});
  // OpenCV draws only horizontal text: draw the z label into a strip and turn it.
  const std::string z_label = "z [m]";
  const cv::Size size = textSize(z_label);
  cv::Mat strip(size.height + 8, size.width + 4, CV_8UC3, cv::Scalar::all(255)), turned;
  cv::putText(strip, z_label, {2, size.height + 2}, kFont, kFontScale, kText, 1, cv::LINE_AA);
  cv::rotate(strip, turned, cv::ROTATE_90_COUNTERCLOCKWISE);
  const cv::Point corner(std::max(0, area.x - 75), area.y + area.height / 2 - turned.rows / 2);
  turned.copyTo((*image)(cv::Rect(corner, turned.size())));
}

void drawPath(const PlotFrame& frame, const std::vector<Eigen::Vector3d>& points, const cv::Scalar& colour,
              int thickness, cv::Mat* image) {
  if (points.empty()) return;
  std::vector<cv::Point> pixels;
  pixels.reserve(points.size());
  for (const auto& p : points) pixels.push_back(frame.pixel(p.x(), p.z()));
  cv::polylines(*image, pixels, false, colour, thickness, cv::LINE_AA, kShift);
  cv::circle(*image, pixels.front(), 5 << kShift, colour, cv::FILLED, cv::LINE_AA, kShift);
}

void drawLegend(const TopDownPlotOptions& options, const cv::Rect& area, cv::Mat* image) {
  const int width = std::max(textSize(options.gt_label).width, textSize(options.est_label).width) + 50;
  const cv::Point corner(area.x + area.width - width, 8);
  cv::rectangle(*image, cv::Rect(corner, cv::Size(width, 46)), kText, 1);
  const std::pair<const std::string*, cv::Scalar> rows[] = {{&options.gt_label, kGroundTruth},
                                                            {&options.est_label, kEstimate}};
  for (int i = 0; i < 2; ++i) {
    const int v = corner.y + 14 + 20 * i;
    cv::line(*image, {corner.x + 8, v}, {corner.x + 36, v}, rows[i].second, 4 - 2 * i, cv::LINE_AA);
    putText(image, *rows[i].first, {corner.x + 44, v + 5});
  }
}

}  // namespace

std::string TopDownPlotOptions::validate() const {
  if (width_px < 300 || height_px < 300)
    return "the plot needs at least 300x300 pixels (got " + std::to_string(width_px) + "x" +
           std::to_string(height_px) + ")";
  return "";
}

cv::Mat renderTopDownPlot(const std::vector<Eigen::Vector3d>& gt, const std::vector<Eigen::Vector3d>& est,
                          const TopDownPlotOptions& options) {
  cv::Mat image(options.height_px, options.width_px, CV_8UC3, cv::Scalar::all(255));
  const cv::Rect area(100, 70, options.width_px - 130, options.height_px - 140);
  const PlotFrame frame = fitFrame(gt, est, area);
  drawAxes(frame, &image);
  drawPath(frame, gt, kGroundTruth, 4, &image);  // wider, so that it shows round an estimate on top of it
  drawPath(frame, est, kEstimate, 2, &image);
  cv::rectangle(image, area, kText, 1);
  putText(&image, options.title, {area.x, 30});
  drawLegend(options, area, &image);
  return image;
}

}  // namespace semantic_edge_vo
