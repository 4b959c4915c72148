#pragma once
// Test fixture: a random scene of 3D line segments with classes, and what two cameras see of it.
#include <random>

#include "semantic_edge_vo/frontend/edge_registration.h"
#include "semantic_edge_vo/common/edge_set.h"

namespace semantic_edge_vo {
namespace testing_scenes {

/// 3D line segments with classes, seen by two cameras: edges of the target image (for its field)
/// and reference edges with exact depth.
struct LineScene {
  struct Segment {
    Eigen::Vector3d a, b;
    int label;
  };
  std::vector<Segment> segments;

  static LineScene random(int count, int classes, std::uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> x(-12, 12), y(-4, 3), z(6, 40), len(1.0, 6.0), dir(-1, 1);
    std::uniform_int_distribution<int> label(0, classes - 1);
    LineScene scene;
    for (int i = 0; i < count; ++i) {
      const Eigen::Vector3d a(x(rng), y(rng), z(rng));
      const Eigen::Vector3d d = Eigen::Vector3d(dir(rng), dir(rng), 0.3 * dir(rng)).normalized();
      scene.segments.push_back({a, a + len(rng) * d, label(rng)});
    }
    return scene;
  }

  /// Edge pixels of the segments seen from a camera at T_cam_world, one per ~0.5 px.
  EdgeSet edgesIn(const PinholeCamera& camera, const Eigen::Isometry3d& T_cam_world) const {
    EdgeSet edges;
    for (const Segment& s : segments) {
      const Eigen::Vector3d a = T_cam_world * s.a, b = T_cam_world * s.b;
      if (a.z() < 1 || b.z() < 1) continue;
      const Eigen::Vector2d pa = camera.project(a), pb = camera.project(b);
      const int steps = static_cast<int>((pb - pa).norm() * 2) + 1;
      const Eigen::Vector2d t = (pb - pa).normalized();
      for (int k = 0; k <= steps; ++k) {
        const Eigen::Vector3d p = T_cam_world * (s.a + (s.b - s.a) * k / steps);
        const Eigen::Vector2d q = camera.project(p);
        if (!camera.contains(q.x(), q.y(), 1)) continue;
        edges.push_back(static_cast<float>(q.x()), static_cast<float>(q.y()), static_cast<float>(-t.y()),
                        static_cast<float>(t.x()), 1.0f, 1u << s.label);
      }
    }
    return edges;
  }
  /// Reference edges (points in the reference optical frame) every `spacing` metres.
  std::vector<ReferenceEdge> referenceEdges(const PinholeCamera& camera, const Eigen::Isometry3d& T_ref_world) const {
    std::vector<ReferenceEdge> out;
    for (const Segment& s : segments) {
      const Eigen::Vector3d a = T_ref_world * s.a, b = T_ref_world * s.b;
      if (a.z() < 1 || b.z() < 1) continue;
      const Eigen::Vector2d t = (camera.project(b) - camera.project(a)).normalized();
      for (int k = 0; k <= 8; ++k) {
        const Eigen::Vector3d p = a + (b - a) * k / 8.0;
        const Eigen::Vector2d q = camera.project(p);
        if (!camera.contains(q.x(), q.y(), 1)) continue;
        out.push_back({p, Eigen::Vector2d(-t.y(), t.x()), 1u << s.label, 1.0});
      }
    }
    return out;
  }
};

inline Eigen::Isometry3d pose(double tx, double ty, double tz, double yaw_deg, double pitch_deg = 0) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.rotate(Eigen::AngleAxisd(yaw_deg * M_PI / 180, Eigen::Vector3d::UnitY()) *
           Eigen::AngleAxisd(pitch_deg * M_PI / 180, Eigen::Vector3d::UnitX()));
  T.translation() << tx, ty, tz;
  return T;
}

}  // namespace testing_scenes
}  // namespace semantic_edge_vo
