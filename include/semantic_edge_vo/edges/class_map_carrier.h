#pragma once
#include <deque>
#include <string>

#include <opencv2/core/mat.hpp>

#include "semantic_edge_vo/edges/class_evidence.h"

namespace cv {
class DISOpticalFlow;  // opencv2/video, kept out of this header
}

namespace semantic_edge_vo {

struct ClassMapCarrierOptions {
  /// Scale of the images the optical flow is computed on: 0.5 halves the time and keeps the
  /// boundaries within a pixel or two, which the intake's side_distance reads across anyway.
  double flow_scale = 0.5;
  /// A class map older than this is not carried: the frame has none (on_missing_classes), s.
  double max_age = 1.0;
  /// Images kept for class maps still to come (the segmenter's latency, in frames, at most).
  int remembered_images = 20;
  /// A pixel whose flow to the map's image and back misses it by more keeps its place, full-resolution px.
  double max_loop_error = 2.0;

  std::string validate() const;
};

/// Carries the newest class map to the frames after its image along the dense optical flow (DIS)
/// from each frame to that image, so that a segmenter slower than the camera labels every frame: a
/// pixel takes the class of the pixel it came from. The flow needs neither a pose nor depths (it
/// keeps working while tracking is lost or the map is wrong) and moves the classes of other cars
/// with them, which the camera's motion would not. Where the flow there and back disagrees (the
/// repeated windows of a facade, occlusions) a pixel keeps its place: on synthetic city drives the
/// carried map then labels the frame's edge pixels right at least as often as the stale map, 1 to 6
/// points more often 1 to 4 frames later.
class ClassMapCarrier {
 public:
  explicit ClassMapCarrier(const ClassMapCarrierOptions& options = ClassMapCarrierOptions());
  ~ClassMapCarrier();
  ClassMapCarrier(ClassMapCarrier&&) noexcept;
  ClassMapCarrier& operator=(ClassMapCarrier&&) noexcept;

  /// The next frame's image (CV_8UC1), by its time; kept for a class map of it that may come later.
  void addImage(double time, const cv::Mat& gray);
  /// The class map of the image of `time` (copied). False, and not taken, when that image is not
  /// remembered (older than the remembered images, or never added) or is older than the newest map.
  bool setClassMap(double time, const ClassEvidence& evidence);
  /// The class map carried to the newest image, of `time`: the map itself when it is of this image.
  /// False when there is none within max_age, or `time` is not the newest image's.
  /// @param[out] age how much older than the image the map is, s
  bool carryTo(double time, ClassEvidence* carried, double* age) const;
  /// Forgets the images and the map (the stream started over).
  void clear();

 private:
  struct RememberedImage {
    double time;
    cv::Mat small;  ///< at flow_scale
  };
  /// Where each pixel of the newest image was in the map's image.
  void measurePositions();

  ClassMapCarrierOptions options_;
  std::deque<RememberedImage> images_;
  bool has_map_ = false;
  double map_time_ = 0.0;
  ClassEvidence map_;
  cv::Mat map_image_;  ///< the map's image at flow_scale
  /// CV_32FC2 at flow_scale: where each pixel of the newest image was in the map's image.
  cv::Mat positions_;
  cv::Ptr<cv::DISOpticalFlow> flow_;
};

}  // namespace semantic_edge_vo
