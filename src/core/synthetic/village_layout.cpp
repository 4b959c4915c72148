#include <cmath>

#include "semantic_edge_vo/synthetic/props.h"
#include "semantic_edge_vo/synthetic/scene_layout.h"

namespace semantic_edge_vo {
namespace synthetic {

void buildVillageChunk(ChunkContext* chunk) {
  Random& random = chunk->random;
  const double w = chunk->road.paved_half_width;
  const Surface hedge{Material::kFoliage, 8, 0, false};
  const Surface wood{Material::kWood, 4, 0, false};
  for (double side : {-1.0, 1.0}) {
    // Trees: a dense belt near the road, a sparser forest edge behind it.
    for (int i = 0; i < 9; ++i) {
      const double s = random.uniform(chunk->s0, chunk->s1);
      const double offset = i < 6 ? random.uniform(w + 2.5, w + 18.0) : random.uniform(w + 25.0, w + 90.0);
      const double height = random.uniform(5.0, 15.0);
      const double crown = random.uniform(0.2, 0.35) * height;
      const Eigen::Isometry3d pose = chunk->poseAt(s, side * offset, random.uniform(0.0, 6.28));
      if (chunk->clearOfRoad(pose, 2.0 * crown, 2.0 * crown, 0.0))
        addTree(chunk->out, pose, height, crown, random.chance(0.3), chunk->variant());
    }
    for (int i = 0; i < 4; ++i) {  // bushes
      const double s = random.uniform(chunk->s0, chunk->s1);
      const double size = random.uniform(0.6, 1.4);
      const Eigen::Isometry3d pose = chunk->poseAt(s, side * random.uniform(w + 1.5, w + 12.0), random.uniform(0.0, 6.28));
      if (chunk->clearOfRoad(pose, 2.0 * size, 2.0 * size, 0.0))
        addTree(chunk->out, pose, 1.6 * size, size, false, chunk->variant());
    }
    if (random.chance(0.45)) {  // a hedge or a fence along the road
      const double length = random.uniform(8.0, 20.0);
      const double s = random.uniform(chunk->s0, chunk->s1 - length);
      const bool fence = random.chance(0.4);
      const double offset = side * (w + random.uniform(1.5, 3.0));
      for (double sa = s; sa < s + length - 1e-9; sa += 2.0) {
        const double sb = std::min(s + length, sa + 2.0);
        const double height = fence ? 1.1 : 1.4;
        const double thickness = fence ? 0.04 : 0.8;
        for (double face : {-1.0, 1.0})
          chunk->addStrip(sa, sb, {offset + face * thickness, 0.0}, {offset + face * thickness, height}, {face, 0.0, 0.0},
                          fence ? wood : hedge);
        chunk->addStrip(sa, sb, {offset - thickness, height}, {offset + thickness, height}, {0.0, -1.0, 0.0},
                        fence ? wood : hedge);
      }
    }
    if (random.chance(0.35)) {  // a house, set back from the road
      const double width = random.uniform(7.0, 10.0), length = random.uniform(8.0, 13.0);
      const double s = random.uniform(chunk->s0 + 0.5 * length, chunk->s1 - 0.5 * length);
      const Eigen::Isometry3d pose =
          chunk->poseAt(s, side * (w + random.uniform(6.0, 14.0) + 0.5 * width), random.uniform(-0.15, 0.15));
      if (chunk->clearOfRoad(pose, width + 1.0, length + 1.0, 1.0))
        addHouse(chunk->out, pose, width, random.uniform(4.5, 6.5), length, chunk->variant());
    }
    if (random.chance(0.15)) {
      const double s = random.uniform(chunk->s0, chunk->s1);
      addSign(chunk->out, chunk->poseAt(s, side * (w + 1.0), side > 0 ? 0.0 : 3.14159), 1.8, 0.6, 0.6, 1,
              chunk->variant());
    }
  }
  // Utility poles on the right, every 40 m or so.
  for (double s = chunk->s0 + random.uniform(0.0, 40.0); s < chunk->s1; s += 40.0)
    addPole(chunk->out, chunk->poseAt(s, w + 1.2), 8.0, 0.13, true);
}

}  // namespace synthetic
}  // namespace semantic_edge_vo
