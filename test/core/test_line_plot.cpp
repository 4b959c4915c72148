#include <gtest/gtest.h>

#include "semantic_edge_vo/eval/line_plot.h"

namespace semantic_edge_vo {
namespace {

TEST(LinePlot, NiceTicksAreRoundAndCoverTheRange) {
  EXPECT_EQ(niceTicks(0.0, 5.0), (std::vector<double>{0, 1, 2, 3, 4, 5}));
  const auto ticks = niceTicks(0.0, 0.93);
  EXPECT_DOUBLE_EQ(ticks.front(), 0.0);
  EXPECT_GE(ticks.back(), 0.93);
  EXPECT_NEAR(ticks[1] - ticks[0], 0.2, 1e-12);
}

TEST(LinePlot, DrawsEachSeriesInItsColour) {
  PlotSeries a{"a", {0, 1, 2}, {0, 0.5, 1}, {{255, 0, 0}}};
  PlotSeries b{"b", {0, 1, 2}, {1, 0.5, 0}, {{0, 0, 255}}};
  const cv::Mat plot = renderLinePlot({a, b}, LinePlotOptions{640, 480, "t", "x", "y", true});
  ASSERT_EQ(plot.type(), CV_8UC3);
  int blue = 0, red = 0;
  for (auto it = plot.begin<cv::Vec3b>(); it != plot.end<cv::Vec3b>(); ++it) {
    blue += (*it == cv::Vec3b(255, 0, 0));
    red += (*it == cv::Vec3b(0, 0, 255));
  }
  EXPECT_GT(blue, 200);
  EXPECT_GT(red, 200);
}

}  // namespace
}  // namespace semantic_edge_vo
