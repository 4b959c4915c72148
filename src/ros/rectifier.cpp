#include "semantic_edge_vo/ros/rectifier.h"

#include <algorithm>

#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include "semantic_edge_vo/ros/conversions.h"

namespace semantic_edge_vo {
namespace {

bool sameCalibration(const sensor_msgs::CameraInfo& a, const sensor_msgs::CameraInfo& b) {
  return a.width == b.width && a.height == b.height && a.distortion_model == b.distortion_model && a.D == b.D && a.K == b.K &&
         a.R == b.R && a.P == b.P;
}

template <std::size_t N>
bool allZero(const boost::array<double, N>& values) {
  return std::all_of(values.begin(), values.end(), [](double v) { return v == 0.0; });
}

}  // namespace

std::string Rectifier::prepare(const sensor_msgs::CameraInfo& info) {
  if (!map1_.empty() && sameCalibration(info, calibration_)) return "";
  map1_ = cv::Mat();
  map2_ = cv::Mat();
  if (info.width == 0 || info.height == 0) return "camera_info has no image size";
  // The rectified camera is the one the odometry reads from any camera_info (P, or K where unset).
  const PinholeCamera target = cameraFromInfo(info);
  // A binned or region-of-interest image is smaller than the sensor, whose maps these would be.
  if (target.width != static_cast<int>(info.width) || target.height != static_cast<int>(info.height))
    return "binned or region-of-interest images are not rectified here (binning " + std::to_string(info.binning_x) + "x" +
           std::to_string(info.binning_y) + ", roi " + std::to_string(info.roi.width) + "x" + std::to_string(info.roi.height) +
           "): rectify them with image_proc and set rectify false";
  if (info.K[0] <= 0.0 || info.K[4] <= 0.0) return "camera_info K has no focal length";
  const cv::Matx33d K(info.K.data());
  const cv::Matx33d R = allZero(info.R) ? cv::Matx33d::eye() : cv::Matx33d(info.R.data());
  const cv::Matx33d P(target.fx, 0.0, target.cx, 0.0, target.fy, target.cy, 0.0, 0.0, 1.0);
  const cv::Size size(static_cast<int>(info.width), static_cast<int>(info.height));
  const cv::Mat D(info.D, true);
  const std::string& model = info.distortion_model;
  if (model == "equidistant") {
    if (info.D.size() != 4) return "equidistant distortion needs 4 coefficients, camera_info has " + std::to_string(info.D.size());
    cv::fisheye::initUndistortRectifyMap(K, D, R, P, size, CV_16SC2, map1_, map2_);
  } else if (model == "plumb_bob" || model == "rational_polynomial" || (model.empty() && info.D.empty())) {
    cv::initUndistortRectifyMap(K, info.D.empty() ? cv::Mat() : D, R, P, size, CV_16SC2, map1_, map2_);
  } else {
    return "distortion model '" + model + "' is not supported (plumb_bob, rational_polynomial, equidistant)";
  }
  calibration_ = info;
  return "";
}

void Rectifier::rectify(const cv::Mat& image, cv::Mat* rectified, bool nearest) const {
  // Nearest neighbour reads the integer map alone: given the interpolation table too, OpenCV 4.6
  // samples the wrong pixels (checked: an identity calibration scrambled every pixel).
  if (nearest) cv::remap(image, *rectified, map1_, cv::noArray(), cv::INTER_NEAREST, cv::BORDER_CONSTANT);
  else cv::remap(image, *rectified, map1_, map2_, cv::INTER_LINEAR, cv::BORDER_CONSTANT);
}

sensor_msgs::CameraInfo Rectifier::rectifiedInfo() const {
  return cameraInfoOf(cameraFromInfo(calibration_), calibration_.header.frame_id);
}

}  // namespace semantic_edge_vo
