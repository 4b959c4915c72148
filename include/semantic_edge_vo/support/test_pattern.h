#pragma once
#include <cstdint>

#include <opencv2/core/mat.hpp>

namespace semantic_edge_vo {

/// A deterministic moving test pattern (textured shapes sliding over a shaded background, with
/// sensor noise): an image stream for smoke tests and the demo until a real scene is rendered.
/// @param[in] frame_index frame number; the pattern moves 4 px right and 1 px down per frame
/// @return 8-bit grayscale image of width x height
cv::Mat renderTestPattern(int frame_index, int width, int height, std::uint32_t seed = 1);

}  // namespace semantic_edge_vo
