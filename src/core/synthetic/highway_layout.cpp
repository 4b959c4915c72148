#include <algorithm>
#include <cmath>

#include "semantic_edge_vo/synthetic/props.h"
#include "semantic_edge_vo/synthetic/scene_layout.h"

namespace semantic_edge_vo {
namespace synthetic {

void buildHighwayChunk(ChunkContext* chunk) {
  Random& random = chunk->random;
  const double w = chunk->road.paved_half_width;
  const Surface post{Material::kGuardRail, 4, 0, false};
  const Surface wall{Material::kConcrete, 3, 0, false};
  for (double side : {-1.0, 1.0}) {
    // Guard rail posts every 2 m.
    for (double s = std::ceil(chunk->s0 / 2.0) * 2.0; s < chunk->s1; s += 2.0)
      addBox(chunk->out, chunk->poseAt(s, side * (w + 0.5)), {0.12, 0.75, 0.12}, BoxSurfaces::uniform(post));
    if (random.chance(0.12)) {  // a large direction sign on two posts
      const double s = random.uniform(chunk->s0, chunk->s1);
      addSign(chunk->out, chunk->poseAt(s, side * (w + 3.5), side > 0 ? 0.0 : 3.14159), random.uniform(2.5, 4.0),
              random.uniform(3.0, 5.0), random.uniform(1.8, 2.8), 2, chunk->variant());
    }
    if (random.chance(0.2)) {  // a small sign (speed limit)
      const double s = random.uniform(chunk->s0, chunk->s1);
      addSign(chunk->out, chunk->poseAt(s, side * (w + 1.5), side > 0 ? 0.0 : 3.14159), 2.0, 0.8, 0.8, 1,
              chunk->variant());
    }
    if (random.chance(0.15)) {  // a noise barrier wall
      const double length = random.uniform(30.0, chunk->s1 - chunk->s0);
      const double s = random.uniform(chunk->s0, chunk->s1 - length);
      const double offset = side * (w + 4.0), height = random.uniform(2.5, 4.0);
      for (double sa = s; sa < s + length - 1e-9; sa += 2.5) {
        const double sb = std::min(s + length, sa + 2.5);
        chunk->addStrip(sa, sb, {offset, 0.0}, {offset, height}, {-side, 0.0, 0.0}, wall);
        chunk->addStrip(sa, sb, {offset, height}, {offset + side * 0.3, height}, {0.0, -1.0, 0.0}, wall);
      }
    }
    for (int i = 0; i < 3; ++i) {  // sparse roadside trees and bushes
      const double s = random.uniform(chunk->s0, chunk->s1);
      const double height = random.uniform(2.0, 14.0);
      const double crown = random.uniform(0.2, 0.35) * height;
      const Eigen::Isometry3d pose = chunk->poseAt(s, side * random.uniform(w + 8.0, w + 70.0), random.uniform(0.0, 6.28));
      if (chunk->clearOfRoad(pose, 2.0 * crown, 2.0 * crown, 1.0))
        addTree(chunk->out, pose, height, crown, random.chance(0.4), chunk->variant());
    }
  }
  // Lamp posts on the median, arms over one carriageway and the other in turn.
  for (double s = std::ceil(chunk->s0 / 60.0) * 60.0; s < chunk->s1; s += 60.0)
    addStreetLamp(chunk->out, chunk->poseAt(s, 0.0, static_cast<long long>(s / 60.0) % 2 ? 3.14159 : 0.0), 10.0);
}

}  // namespace synthetic
}  // namespace semantic_edge_vo
