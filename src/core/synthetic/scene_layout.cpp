#include "semantic_edge_vo/synthetic/scene_layout.h"

#include <algorithm>
#include <cmath>

namespace semantic_edge_vo {
namespace synthetic {

Eigen::Isometry3d ChunkContext::poseAt(double s, double offset, double yaw) const {
  const RoutePoint point = route.at(s);
  return groundPose(point.position + offset * point.right, point.heading + yaw);
}

bool ChunkContext::clearOfRoad(const Eigen::Isometry3d& pose, double width, double length, double margin) const {
  const double keep_out = road.builtHalfWidth() + margin;
  const double window = 60.0 + std::max(width, length);
  const double s_mid = 0.5 * (s0 + s1);
  for (double x : {-0.5, 0.0, 0.5})
    for (double z : {-0.5, 0.0, 0.5}) {
      const Eigen::Vector3d corner = pose * Eigen::Vector3d(x * width, 0.0, z * length);
      if (route.distanceToCentreline(corner, s_mid - window - 100.0, s_mid + window + 100.0) < keep_out) return false;
    }
  return true;
}

void ChunkContext::addStrip(double sa, double sb, const Eigen::Vector2d& from, const Eigen::Vector2d& to,
                            const Eigen::Vector3d& outward_hint, const Surface& surface) {
  const RoutePoint a = route.at(sa), b = route.at(sb);
  auto point = [](const RoutePoint& p, const Eigen::Vector2d& cross) {
    return Eigen::Vector3d(p.position + cross.x() * p.right - cross.y() * Eigen::Vector3d::UnitY());
  };
  const Eigen::Vector3d outward = outward_hint.x() * a.right + outward_hint.y() * Eigen::Vector3d::UnitY() +
                                  outward_hint.z() * a.tangent;
  const bool horizontal = std::abs(from.y() - to.y()) < 1e-9;
  if (horizontal) {
    addPolygon(out, {point(a, from), point(a, to), point(b, to), point(b, from)}, outward, surface,
               a.position - sa * a.tangent, a.right, a.tangent);
  } else {
    addPolygon(out, {point(a, from), point(a, to), point(b, to), point(b, from)}, outward, surface,
               a.position + from.x() * a.right - sa * a.tangent, a.tangent, up());
  }
}

void buildRoadSurface(ChunkContext* chunk, SceneType type) {
  const RoadProfile& road = chunk->road;
  const double w = road.paved_half_width;
  const Surface asphalt{Material::kAsphalt, 0, 0, false};
  const Surface curb{Material::kCurb, 1, 0, false};
  const Surface pavement{Material::kSidewalk, 1, 0, false};
  const Surface barrier{Material::kConcrete, 3, 0, false};
  const Surface rail{Material::kGuardRail, 4, 0, true};
  const double up_y = -1.0;  // the y component of an upward hint
  for (double sa = chunk->s0; sa < chunk->s1 - 1e-9;) {
    // Shorter steps in sharp turns keep the strips close to the curve.
    const double curvature = std::abs(chunk->route.at(sa).curvature);
    const double sb = std::min(chunk->s1, sa + (curvature > 0.01 ? 1.0 : 2.5));
    chunk->addStrip(sa, sb, {-w, 0.0}, {w, 0.0}, {0.0, up_y, 0.0}, asphalt);
    if (road.curb_height > 0.0) {
      const double h = road.curb_height, outer = w + road.sidewalk_width;
      for (double side : {-1.0, 1.0}) {
        chunk->addStrip(sa, sb, {side * w, 0.0}, {side * w, h}, {-side, 0.0, 0.0}, curb);
        chunk->addStrip(sa, sb, {side * w, h}, {side * outer, h}, {0.0, up_y, 0.0}, pavement);
        chunk->addStrip(sa, sb, {side * outer, h}, {side * outer, -0.05}, {side, 0.0, 0.0}, curb);
      }
    }
    if (type == SceneType::kHighway) {
      // Concrete median barrier on the centreline, guard rails beyond the hard shoulders.
      for (double side : {-1.0, 1.0}) {
        chunk->addStrip(sa, sb, {side * 0.35, 0.0}, {side * 0.2, 0.85}, {side, 0.0, 0.0}, barrier);
        chunk->addStrip(sa, sb, {side * (w + 0.4), 0.45}, {side * (w + 0.4), 0.8}, {-side, 0.0, 0.0}, rail);
      }
      chunk->addStrip(sa, sb, {-0.2, 0.85}, {0.2, 0.85}, {0.0, up_y, 0.0}, barrier);
    }
    sa = sb;
  }
}

}  // namespace synthetic
}  // namespace semantic_edge_vo
