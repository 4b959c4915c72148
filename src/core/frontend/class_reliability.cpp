#include "semantic_edge_vo/frontend/class_reliability.h"

#include <string>

namespace semantic_edge_vo {
namespace {

/// A frame's edge this near the projected point is the point's edge seen again, px (full
/// resolution): a tracked pose and a measured depth place it within about a pixel.
constexpr float kAgreementRadius = 2.0f;
/// Each frame keeps this share of the counts before: about the last ten frames (1 s at 10 Hz) decide.
constexpr double kDecay = 0.9;
/// Points of a class seen (decayed count) before its agreement is believed; until then it is not relied on.
constexpr double kMinSeen = 30.0;

}  // namespace

std::string ClassReliabilityOptions::validate() const {
  if (!(min_agreement >= 0.0)) return "min_agreement must be >= 0 (got " + std::to_string(min_agreement) + ")";
  return {};
}

void ClassReliability::observe(const Keyframe& keyframe, const Eigen::Isometry3d& T_frame_kf, const NearestNeighborFieldView& field) {
  if (field.kind != FieldKind::kSnnf || field.all_edges_layer <= 0 || field.levels.empty()) return;
  for (std::size_t c = 0; c < seen_.size(); ++c) {
    agreed_[c] *= kDecay;
    seen_[c] *= kDecay;
  }
  const FieldLevelView& level = field.levels[0];
  const PinholeCamera& camera = keyframe.frame->pyramid->level(0).camera;
  const int classes = field.all_edges_layer;
  for (const MapPoint& point : keyframe.points) {
    if (!point.isEdge() || !point.hasDepth()) continue;
    const Eigen::Vector3d p = T_frame_kf * camera.backProject(point.u, point.v, 1.0 / point.inverse_depth);
    if (p.z() <= 1e-3) continue;
    const Eigen::Vector2d pixel = camera.project(p);
    const float x = static_cast<float>(pixel.x()), y = static_cast<float>(pixel.y());
    if (!camera.contains(x, y) || !level.anyWithin(field.all_edges_layer, x, y, kAgreementRadius)) continue;
    for (int c = 0; c < classes; ++c) {
      if (!((point.class_mask >> c) & 1u)) continue;
      seen_[static_cast<std::size_t>(c)] += 1.0;
      if (level.anyWithin(c, x, y, kAgreementRadius)) agreed_[static_cast<std::size_t>(c)] += 1.0;
    }
  }
}

double ClassReliability::agreement(int class_index) const {
  const auto c = static_cast<std::size_t>(class_index);
  return seen_[c] > 0.0 ? agreed_[c] / seen_[c] : 0.0;
}

bool ClassReliability::reliable(int class_index) const {
  if (options_.min_agreement <= 0.0) return true;
  return seen_[static_cast<std::size_t>(class_index)] >= kMinSeen && agreement(class_index) >= options_.min_agreement;
}

std::uint32_t ClassReliability::fieldLayers(std::uint32_t class_mask, int all_edges_layer) const {
  if (all_edges_layer <= 0) return class_mask;  // no layer to fall back to (one class is its own)
  std::uint32_t relied = 0;
  for (int c = 0; c < all_edges_layer; ++c)
    if (((class_mask >> c) & 1u) && reliable(c)) relied |= 1u << c;
  return relied ? relied : 1u << all_edges_layer;
}

}  // namespace semantic_edge_vo
