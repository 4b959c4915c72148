#pragma once
#include <memory>
#include <string>
#include <vector>

#include "semantic_edge_vo/edges/class_evidence.h"
#include "semantic_edge_vo/frontend/image_pyramid.h"
#include "semantic_edge_vo/backend/map_point.h"
#include "semantic_edge_vo/fields/nearest_neighbor_field.h"
#include "semantic_edge_vo/frontend/point_sampler.h"
#include "semantic_edge_vo/edges/semantic_edge_extractor.h"

namespace semantic_edge_vo {

/// What the odometry needs of one frame: its pyramid, its nearest-neighbour field (absent for
/// photometric-only odometry) and the points it would host if it became a keyframe.
struct OdometryFrame {
  int index = 0;
  double time = 0.0;  ///< s
  std::shared_ptr<const ImagePyramid> pyramid;
  bool has_field = false;
  NearestNeighborFieldView field;              ///< valid while field_storage lives
  std::shared_ptr<const void> field_storage;   ///< owns what `field` views (built data or a message)
  std::vector<MapPoint> candidates;            ///< sampled edge points (with classes) and supportive points, no depth yet
  /// false: the intake had no class map for it (its edges have no class): matched in the field's
  /// all-edges layer, as ANNF matches, and no evidence on the classes' reliability
  bool classes_known = true;

  const NearestNeighborFieldView* fieldOrNull() const { return has_field ? &field : nullptr; }
};

/// Sampled edges and supportive pixels as map-point candidates (inverse depth still unknown).
std::vector<MapPoint> candidatesFrom(const EdgeSetView& edges, const std::vector<std::uint32_t>& sampled_edges,
                                     const std::vector<float>& support_u, const std::vector<float>& support_v);

struct FrameBuilderOptions {
  SemanticEdgeOptions intake;   ///< canny | fused | semantic_edges
  PointSamplerOptions sampler;
  FieldOptions field;
  bool use_field = true;        ///< false: photometric-only odometry (field kind "none")
  int pyramid_levels = 4;

  std::string validate() const;
};

/// Builds OdometryFrames from images in-process (the offline runner; the nodelets build them from
/// their messages instead).
class FrameBuilder {
 public:
  FrameBuilder(const FrameBuilderOptions& options, const PinholeCamera& camera, std::vector<std::string> class_names);

  /// @param[in] gray CV_8UC1 image of the camera's size
  /// @param[in] classes class evidence (ignored in canny mode; empty: Canny edges of no class)
  /// @param[out] error named reason when the inputs are unusable
  std::shared_ptr<const OdometryFrame> build(int index, double time, const cv::Mat& gray, const ClassEvidence& classes,
                                             ExtractionError* error) const;
  /// The classes the frames' class masks refer to: the class table, or {"edge"} in canny mode.
  std::vector<std::string> classNames() const;

 private:
  FrameBuilderOptions options_;
  PinholeCamera camera_;
  std::vector<std::string> class_names_;
  PointSampler sampler_;
};

}  // namespace semantic_edge_vo
