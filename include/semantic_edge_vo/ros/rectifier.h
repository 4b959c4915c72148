#pragma once
#include <string>

#include <opencv2/core/mat.hpp>
#include <sensor_msgs/CameraInfo.h>

namespace semantic_edge_vo {

/// Undistorts and rectifies the images of a calibrated camera, as image_proc's rectify nodelet does
/// (which Debian ships without its plugin description, so it cannot be loaded there): the image the
/// camera of camera_info.P sees. Distortion models plumb_bob, rational_polynomial (OpenCV's
/// undistortion) and equidistant (fisheye). The maps are computed again only when the calibration
/// changes.
class Rectifier {
 public:
  /// Prepares the maps for images of `info`; "" or what is wrong (distortion model, matrices).
  std::string prepare(const sensor_msgs::CameraInfo& info);
  /// `image` (the size of the last prepare(), any number of channels) rectified into `rectified`,
  /// bilinear, or nearest for maps of class indices or bits; outside the original image: zero.
  void rectify(const cv::Mat& image, cv::Mat* rectified, bool nearest = false) const;
  /// CameraInfo of the rectified images (cameraInfoOf the camera cameraFromInfo reads from the
  /// calibration): its intrinsics in K and P, no distortion, R identity.
  sensor_msgs::CameraInfo rectifiedInfo() const;
  /// Whether prepare() made maps.
  bool ready() const { return !map1_.empty(); }

 private:
  sensor_msgs::CameraInfo calibration_;  ///< what the maps were made for
  cv::Mat map1_, map2_;
};

}  // namespace semantic_edge_vo
