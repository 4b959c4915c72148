#include "semantic_edge_vo/support/test_pattern.h"

#include <random>

#include <opencv2/imgproc.hpp>

namespace semantic_edge_vo {

cv::Mat renderTestPattern(int frame_index, int width, int height, std::uint32_t seed) {
  // Shapes on a canvas larger than the image, so the view slides over fresh content.
  const int shift_x = 4 * frame_index, shift_y = frame_index;
  cv::Mat image(height, width, CV_8UC1);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) image.at<std::uint8_t>(y, x) = static_cast<std::uint8_t>(60 + (x + y) % 256 / 4);

  std::mt19937 shapes(seed);
  std::uniform_int_distribution<int> px(-2 * width, 2 * width), py(-height, 2 * height);
  std::uniform_int_distribution<int> size(8, 60), gray(20, 235), kind(0, 2);
  for (int i = 0; i < 400; ++i) {
    const cv::Point centre(px(shapes) - shift_x, py(shapes) - shift_y);
    const int s = size(shapes);
    const cv::Scalar level(gray(shapes));
    switch (kind(shapes)) {
      case 0: cv::rectangle(image, cv::Rect(centre.x - s, centre.y - s / 2, 2 * s, s), level, cv::FILLED); break;
      case 1: cv::circle(image, centre, s / 2, level, cv::FILLED, cv::LINE_AA); break;
      default: cv::line(image, centre, centre + cv::Point(s, s / 3), level, 3, cv::LINE_AA); break;
    }
  }
  std::mt19937 noise(seed * 7919u + static_cast<std::uint32_t>(frame_index));
  std::normal_distribution<float> sensor(0.0f, 2.0f);
  for (auto it = image.begin<std::uint8_t>(); it != image.end<std::uint8_t>(); ++it)
    *it = cv::saturate_cast<std::uint8_t>(*it + sensor(noise));
  return image;
}

}  // namespace semantic_edge_vo
