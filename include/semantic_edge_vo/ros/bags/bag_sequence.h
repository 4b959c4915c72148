#pragma once
#include <cstddef>
#include <functional>
#include <string>

namespace semantic_edge_vo {

/// A recorded camera to read offline, as a KITTI odometry folder.
struct BagSequenceOptions {
  std::string bag;     ///< the recording
  std::string topic;   ///< sensor_msgs/Image or sensor_msgs/CompressedImage; camera_info beside it (image_transport's name)
  std::string output;  ///< the folder to write (image_0/, calib.txt, times.txt)
  bool rectify = false;  ///< undistort with camera_info (D, K, R, P) first, as EdgeIntake's rectify does
};

/// Writes the images of `topic` as a KITTI odometry folder that run_sequence reads: grayscale
/// image_0/%06d.png, calib.txt with P0 the camera of the topic's first valid camera_info (binning
/// and ROI applied), times.txt of the image stamps (s). Images whose stamp is not after the
/// previous one are skipped and counted. `progress(done, total)` after each image. Returns "" or
/// what is wrong; `frames` and `skipped` get the counts.
std::string writeSequenceFromBag(const BagSequenceOptions& options, const std::function<void(std::size_t, std::size_t)>& progress,
                                 std::size_t* frames, std::size_t* skipped);

}  // namespace semantic_edge_vo
