#pragma once
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "semantic_edge_vo/backend/keyframe.h"
#include "semantic_edge_vo/backend/mapper.h"
#include "semantic_edge_vo/eval/keyframe_depth_check.h"

namespace semantic_edge_vo {

/// Checks the keyframes of a run against a synthetic sequence's true depths (DIR/depth/NNNNNN.png,
/// written by make_synthetic_sequence), twice each:
///  - "new": as soon as the keyframe is made, after its points' first epipolar search (a keyframe made
///    by the initialisation: after the initialisation's frames refined it);
///  - "retired": when the next keyframe is made (or at the end of the run): after the depth filter's
///    updates from the frames tracked against it and the windowed optimisations run so far.
class KeyframeDepthReport {
 public:
  explicit KeyframeDepthReport(std::string depth_folder, double tolerance = kDepthCheckTolerance)
      : depth_folder_(std::move(depth_folder)), tolerance_(tolerance) {}

  /// Call after each Odometry::process with its active keyframe and the windows made since the last
  /// call. Empty on success, else what is wrong with the depth file of a keyframe (the caller may
  /// stop reporting; the odometry is not affected).
  std::string update(const std::shared_ptr<const Keyframe>& active, const std::vector<std::shared_ptr<const KeyframeWindow>>& windows);
  /// Checks the newest keyframe as retired: call once, after the last frame, with the active keyframe.
  void finish(const std::shared_ptr<const Keyframe>& active);
  /// One line per check: frame, stage, counts, scale, median error.
  std::string table() const;
  /// Medians over the keyframes of each stage, one line.
  std::string summary() const;

 private:
  struct Row {
    int frame;
    bool retired;
    DepthCheck check;
  };
  /// The keyframe's true depths (CV_32FC1 metres); empty on success, else what is wrong with the file.
  std::string load(const Keyframe& keyframe, cv::Mat* depth) const;
  void check(const Keyframe& keyframe, const cv::Mat& depth, bool retired);

  std::string depth_folder_;
  double tolerance_;
  std::shared_ptr<const Keyframe> newest_;  ///< checked as new, to be checked again when retired (its latest copy)
  cv::Mat newest_depth_;                    ///< its true depths, read once
  std::vector<Row> rows_;
};

}  // namespace semantic_edge_vo
