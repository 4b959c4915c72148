#pragma once
#include <memory>
#include <string>

#include <opencv2/core/mat.hpp>

#include "semantic_edge_vo/edges/class_evidence.h"
#include "semantic_edge_vo/sequences/kitti_sequence.h"
#include "semantic_edge_vo/edges/segmenter.h"
#include "semantic_edge_vo/edges/semantic_edge_extractor.h"

namespace semantic_edge_vo {

/// Frames of a KITTI odometry folder (or a synthetic sequence, same layout) with the class evidence
/// the intake mode needs: fused reads class labels from `class_probability/` or runs a segmentation
/// network in-process (on `image_2/` colour frames when present, else on the grayscale ones);
/// semantic_edges reads per-class edges from `edge_bitmask/`.
class SequenceInput {
 public:
  /// @param[in] segmenter options of the in-process Segmenter (fused intake); no model_path: none
  /// @return "" or what is wrong, naming the file or folder
  std::string open(const std::string& directory, IntakeMode mode, const SegmenterOptions& segmenter, int classes);

  std::size_t size() const { return sequence_.size(); }
  double time(std::size_t frame) const { return sequence_.times[frame]; }
  const PinholeCamera& camera() const { return camera_; }

  /// Reads frame `frame`: its grayscale image and class evidence. "" or what is wrong.
  std::string read(std::size_t frame, cv::Mat* gray, ClassEvidence* evidence);
  /// Milliseconds the segmenter took on the last frame (0 without one).
  double lastSegmenterMs() const { return segmenter_ms_; }
  /// Whether read() runs a network (then it takes both cores itself) rather than reading files.
  bool segmentsInProcess() const { return segmenter_ != nullptr; }

 private:
  KittiSequence sequence_;
  PinholeCamera camera_;
  IntakeMode mode_ = IntakeMode::kCanny;
  int classes_ = 0;
  bool has_colour_ = false;
  std::unique_ptr<Segmenter> segmenter_;
  double segmenter_ms_ = 0.0;
};

}  // namespace semantic_edge_vo
