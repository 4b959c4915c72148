#pragma once
#include <string>

#include "semantic_edge_vo/config/parameter_loader.h"
#include "semantic_edge_vo/edges/segmenter.h"
#include "semantic_edge_vo/edges/semantic_edge_extractor.h"

namespace semantic_edge_vo {

// Loaders of the semantic intake's and the segmenter's options from a parameter source (names as
// in config/semantic_edge_vo.yaml and the README); each returns the validation error.

/// mode, class_threshold, side_distance, canny/*, edges/threshold, edges/blur_sigma (border: canny/border).
std::string loadSemanticEdgeOptions(ParameterLoader* loader, SemanticEdgeOptions* options);
/// model_path, config_path, format, input_width, input_height, mean, scale, swap_rb, output_channels.
std::string loadSegmenterOptions(ParameterLoader* loader, SegmenterOptions* options);

}  // namespace semantic_edge_vo
