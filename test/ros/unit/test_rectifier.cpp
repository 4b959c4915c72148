#include <cmath>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include "semantic_edge_vo/ros/rectifier.h"

namespace semantic_edge_vo {
namespace {

constexpr int kWidth = 320, kHeight = 240;

sensor_msgs::CameraInfo distortedCamera() {
  sensor_msgs::CameraInfo info;
  info.width = kWidth;
  info.height = kHeight;
  info.distortion_model = "plumb_bob";
  info.D = {-0.30, 0.10, 0.001, -0.002, 0.0};  // strong barrel distortion, as a wide-angle lens
  info.K = {250, 0, 161, 0, 252, 118, 0, 0, 1};
  info.R = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  info.P = {230, 0, 158, 0, 0, 230, 121, 0, 0, 0, 1, 0};  // the rectified camera differs from K
  return info;
}

/// A smooth pattern (bilinear sampling of it is nearly exact), as the rectified camera sees it.
cv::Mat idealImage() {
  cv::Mat image(kHeight, kWidth, CV_8UC1);
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x)
      image.at<std::uint8_t>(y, x) = static_cast<std::uint8_t>(128 + 60 * std::sin(x / 9.0) + 60 * std::cos(y / 7.0));
  return image;
}

/// What the lens gives: each raw pixel shows the ideal image where its undistorted ray lands.
cv::Mat distortedImage(const cv::Mat& ideal, const sensor_msgs::CameraInfo& info) {
  std::vector<cv::Point2f> raw, ideal_pixels;
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) raw.emplace_back(static_cast<float>(x), static_cast<float>(y));
  const cv::Matx33d K(info.K.data()), R(info.R.data());
  const cv::Matx33d P(info.P[0], info.P[1], info.P[2], info.P[4], info.P[5], info.P[6], info.P[8], info.P[9], info.P[10]);
  cv::undistortPoints(raw, ideal_pixels, K, cv::Mat(info.D, true), R, P);
  cv::Mat map_x(kHeight, kWidth, CV_32FC1), map_y(kHeight, kWidth, CV_32FC1);
  for (int i = 0; i < kWidth * kHeight; ++i) {
    map_x.at<float>(i / kWidth, i % kWidth) = ideal_pixels[static_cast<std::size_t>(i)].x;
    map_y.at<float>(i / kWidth, i % kWidth) = ideal_pixels[static_cast<std::size_t>(i)].y;
  }
  cv::Mat distorted;
  cv::remap(ideal, distorted, map_x, map_y, cv::INTER_LINEAR, cv::BORDER_REPLICATE);
  return distorted;
}

/// Mean absolute difference over the central half of the image (its borders fall outside the lens).
double centralDifference(const cv::Mat& a, const cv::Mat& b) {
  const cv::Rect centre(kWidth / 4, kHeight / 4, kWidth / 2, kHeight / 2);
  cv::Mat difference;
  cv::absdiff(a(centre), b(centre), difference);
  return cv::mean(difference)[0];
}

TEST(Rectifier, UndoesALensDistortionIntoThePCamera) {
  const sensor_msgs::CameraInfo info = distortedCamera();
  const cv::Mat ideal = idealImage(), distorted = distortedImage(ideal, info);
  Rectifier rectifier;
  ASSERT_EQ(rectifier.prepare(info), "");
  cv::Mat rectified;
  rectifier.rectify(distorted, &rectified);
  const double before = centralDifference(distorted, ideal), after = centralDifference(rectified, ideal);
  std::printf("rectifier: mean absolute difference to the ideal image, central half: %.2f gray levels distorted, %.2f rectified\n", before,
              after);
  EXPECT_GT(before, 10.0) << "the test distortion must matter";
  EXPECT_LT(after, 2.0);

  const sensor_msgs::CameraInfo out = rectifier.rectifiedInfo();
  EXPECT_EQ(out.K[0], 230.0);
  EXPECT_EQ(out.K[2], 158.0);
  EXPECT_EQ(out.K[5], 121.0);
  for (double d : out.D) EXPECT_EQ(d, 0.0);
}

TEST(Rectifier, AnUndistortedCameraLeavesImagesAndClassMapsAsTheyAre) {
  sensor_msgs::CameraInfo info = distortedCamera();
  info.D.assign(5, 0.0);
  info.P = {info.K[0], 0, info.K[2], 0, 0, info.K[4], info.K[5], 0, 0, 0, 1, 0};
  Rectifier rectifier;
  ASSERT_EQ(rectifier.prepare(info), "");
  cv::Mat image = idealImage(), labels(kHeight, kWidth, CV_8UC2), out;
  cv::randu(labels, 0, 19);
  rectifier.rectify(image, &out);
  EXPECT_EQ(cv::norm(out, image, cv::NORM_INF), 0.0) << "bilinear";
  rectifier.rectify(labels, &out, true);
  EXPECT_EQ(cv::norm(out, labels, cv::NORM_INF), 0.0) << "nearest: class indices unchanged";
}

TEST(Rectifier, RefusesWhatItCannotModel) {
  sensor_msgs::CameraInfo info = distortedCamera();
  info.distortion_model = "mirror";
  Rectifier rectifier;
  EXPECT_NE(rectifier.prepare(info).find("not supported"), std::string::npos);
  info = distortedCamera();
  info.distortion_model = "equidistant";  // needs 4 coefficients, has 5
  EXPECT_NE(rectifier.prepare(info), "");
  info = distortedCamera();
  info.K.fill(0.0);
  EXPECT_NE(rectifier.prepare(info), "");
  info = distortedCamera();
  info.binning_x = info.binning_y = 2;  // the maps would be the full sensor's
  EXPECT_NE(rectifier.prepare(info).find("image_proc"), std::string::npos);
  info = distortedCamera();
  info.roi.x_offset = 16;
  info.roi.width = kWidth / 2;
  info.roi.height = kHeight / 2;
  EXPECT_NE(rectifier.prepare(info).find("image_proc"), std::string::npos);
  info.roi.x_offset = 0;
  info.roi.width = kWidth;  // a region of interest that is the whole image is no region
  info.roi.height = kHeight;
  EXPECT_EQ(rectifier.prepare(info), "");
}

}  // namespace
}  // namespace semantic_edge_vo
