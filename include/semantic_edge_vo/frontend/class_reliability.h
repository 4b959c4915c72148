#pragma once
#include <array>
#include <cstdint>
#include <string>

#include <Eigen/Geometry>

#include "semantic_edge_vo/common/class_table.h"
#include "semantic_edge_vo/backend/keyframe.h"
#include "semantic_edge_vo/fields/nearest_neighbor_field.h"

namespace semantic_edge_vo {

struct ClassReliabilityOptions {
  /// A class is relied on (its SNNF layer matches its points) while its points agree with the frames
  /// at least this often; below, they are matched in the all-edges layer, as ANNF matches every
  /// point. 0: every class relied on (plain SNNF); above 1: none (ANNF association, SNNF's fields).
  double min_agreement = 0.85;

  std::string validate() const;
};

/// How far the classes of a drive's segmentation can be relied on, class by class, measured on the
/// drive itself. A segmenter's labels flicker between frames (at class boundaries, on vegetation,
/// in shadows, far away); an SNNF point whose class the frame's edge there does not have is pulled
/// to another edge of its class, or to none, where ANNF would have matched it. After each trusted
/// frame the keyframe's edge points are projected into it: where the frame has an edge near one
/// (of any class), each of its classes agrees when the frame has an edge of that class there too.
/// The counts decay with every frame, so the verdict follows the scene.
class ClassReliability {
 public:
  explicit ClassReliability(const ClassReliabilityOptions& options) : options_(options) {}

  /// Counts the agreement of the keyframe's edge points with a frame tracked at T_frame_kf, whose
  /// semantic field (SNNF) is `field`; other field kinds are ignored.
  void observe(const Keyframe& keyframe, const Eigen::Isometry3d& T_frame_kf, const NearestNeighborFieldView& field);
  /// The SNNF layers a point of `class_mask` is matched in: its classes that are relied on, or,
  /// when none is, the all-edges layer (`all_edges_layer`; -1: there is none, the classes stay).
  std::uint32_t fieldLayers(std::uint32_t class_mask, int all_edges_layer) const;
  /// Fraction of a class's points that agreed, over the recent frames (0 before any was seen).
  double agreement(int class_index) const;
  bool reliable(int class_index) const;

 private:
  ClassReliabilityOptions options_;
  std::array<double, ClassTable::kMaxClasses> agreed_{}, seen_{};  ///< decaying counts per class
};

}  // namespace semantic_edge_vo
