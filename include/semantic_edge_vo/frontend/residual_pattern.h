#pragma once

namespace semantic_edge_vo {

/// DSO's 8-pixel residual pattern around a point, offsets in pixels (of whichever pyramid level it
/// is applied at); entry 4 is the point itself.
constexpr int kPattern = 8;
constexpr int kPatternOffsets[kPattern][2] = {{0, -2}, {-1, -1}, {1, -1}, {-2, 0}, {0, 0}, {2, 0}, {-1, 1}, {0, 2}};

}  // namespace semantic_edge_vo
