#pragma once
#include <deque>
#include <memory>
#include <string>
#include <vector>

#include "semantic_edge_vo/keyframe.h"
#include "semantic_edge_vo/keyframe_depth_check.h"

namespace semantic_edge_vo {

/// Checks the keyframes of a run against a synthetic sequence's true depths (DIR/depth/NNNNNN.png,
/// written by make_synthetic_sequence): each keyframe once its points are triangulated ("new"), and
/// again when the next keyframe replaces it as the tracking reference ("retired", after the depth
/// filter's updates from the frames tracked against it).
class KeyframeDepthReport {
 public:
  explicit KeyframeDepthReport(std::string depth_folder) : depth_folder_(std::move(depth_folder)) {}

  /// Call after each Odometry::process with its keyframes. Empty on success, else which depth file failed.
  std::string update(const std::deque<std::shared_ptr<Keyframe>>& keyframes);
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
  std::string check(const Keyframe& keyframe, bool retired);

  std::string depth_folder_;
  std::shared_ptr<const Keyframe> newest_;  ///< checked as new, to be checked again when retired
  std::vector<Row> rows_;
};

}  // namespace semantic_edge_vo
