#pragma once
#include <string>
#include <vector>

#include "semantic_edge_vo/common/class_table.h"
#include "semantic_edge_vo/config/live_options.h"
#include "semantic_edge_vo/backend/odometry.h"
#include "semantic_edge_vo/frontend/odometry_frame.h"
#include "semantic_edge_vo/edges/segmenter.h"

namespace semantic_edge_vo {

/// Every block of a config file laid out like config/semantic_edge_vo.yaml (edge_intake,
/// segmenter, nearest_neighbor_field, tracking, mapping), read with the loaders the nodelets use:
/// what the offline tools run with, and what the shipped file is checked against.
struct GraphConfig {
  FrameBuilderOptions frame;
  OdometryOptions odometry;
  SegmenterOptions segmenter;
  ClassTable classes = ClassTable::cityscapes();
  IntakeStreamOptions intake_stream;
  TfOptions tf;
  LiveMappingOptions live_mapping;
  MapOutputOptions map_output;
  SegmenterOutputOptions segmenter_output;
  std::string summary;                             ///< every option with its value, "(default)" where not set
  std::vector<std::string> changed_from_defaults;  ///< "block/name = value (default d)"
};

/// Reads `path` (empty: every option at its default) into `config`. Returns the first error: a file
/// that is missing or not YAML, a value of the wrong type or out of range, a block or key that no
/// option reads (named, so a typo never silently runs a default).
std::string loadGraphConfig(const std::string& path, GraphConfig* config);

}  // namespace semantic_edge_vo
