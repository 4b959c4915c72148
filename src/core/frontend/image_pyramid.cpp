#include "semantic_edge_vo/frontend/image_pyramid.h"

#include <cmath>

#include <opencv2/imgproc.hpp>

namespace semantic_edge_vo {
namespace {

/// Central differences (0.5 * (I[x+1] - I[x-1])), zero at the border.
void centralDifferences(const cv::Mat& image, cv::Mat* dx, cv::Mat* dy) {
  const cv::Mat kernel = (cv::Mat_<float>(1, 3) << -0.5f, 0.0f, 0.5f);
  cv::filter2D(image, *dx, CV_32F, kernel, cv::Point(-1, -1), 0.0, cv::BORDER_CONSTANT);
  cv::filter2D(image, *dy, CV_32F, kernel.t(), cv::Point(-1, -1), 0.0, cv::BORDER_CONSTANT);
}

}  // namespace

ImagePyramid::ImagePyramid(const cv::Mat& gray, const PinholeCamera& camera, int levels) {
  CV_Assert(gray.type() == CV_8UC1 && levels >= 1);
  levels_.resize(static_cast<std::size_t>(levels));
  for (int l = 0; l < levels; ++l) {
    PyramidLevel& level = levels_[static_cast<std::size_t>(l)];
    level.camera = camera.scaled(std::ldexp(1.0, -l));
    if (l == 0) gray.convertTo(level.intensity, CV_32F);
    else cv::resize(levels_[static_cast<std::size_t>(l - 1)].intensity, level.intensity,
                    cv::Size(level.camera.width, level.camera.height), 0, 0, cv::INTER_AREA);
    cv::Mat dx, dy;
    centralDifferences(level.intensity, &dx, &dy);
    cv::magnitude(dx, dy, level.gradient);
    centralDifferences(level.gradient, &level.gradient_dx, &level.gradient_dy);
  }
}

}  // namespace semantic_edge_vo
