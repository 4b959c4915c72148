#pragma once
#include <cstddef>
#include <functional>
#include <string>

#include <sensor_msgs/CameraInfo.h>

#include "semantic_edge_vo/sequences/kitti_sequence.h"
#include "semantic_edge_vo/ros/bags/sequence_bag_writer.h"

namespace semantic_edge_vo {

/// What kitti_to_bag converts, and how.
struct KittiBagOptions {
  std::string sequence;        ///< KITTI odometry folder (calib.txt, times.txt, image_<camera>/)
  std::string output;          ///< bag file to write (replaced)
  int camera = 0;              ///< 0: image_0 (mono8), 2: image_2 (bgr8)
  std::string poses;           ///< optional KITTI pose file of camera 0 (one line per frame)
  std::string class_labels;    ///< optional folder of %06d.png class labels (readClassLabelsPng)
  std::string edge_bitmask;    ///< optional folder of %06d.png edge bitmasks (readEdgeBitmaskPng)
  double start_time = SequenceBagWriter::kBaseTime;  ///< stamp of times.txt's 0, s
};

/// The complete CameraInfo of a KITTI camera: K = left 3x3 of the projection, P as given, R = I,
/// D = 0 (plumb_bob), the images' size.
sensor_msgs::CameraInfo kittiCameraInfo(const KittiSequence& sequence, int width, int height,
                                        const std::string& frame_id);

/// Writes the sequence into a bag with SequenceBagWriter (image, camera_info, class topics, ground
/// truth moved from camera 0 to the chosen camera). Every input file is checked before the bag is
/// opened; on any error the partial bag is removed. `progress(done, total)` is called once the bag
/// is open (done = 0) and after each frame. Returns "" or what is wrong, naming the file (and line).
std::string writeKittiBag(const KittiBagOptions& options,
                          const std::function<void(std::size_t done, std::size_t total)>& progress);

}  // namespace semantic_edge_vo
