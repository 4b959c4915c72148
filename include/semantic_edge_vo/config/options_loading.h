#pragma once
#include <string>

#include "semantic_edge_vo/edges/canny_edge_detector.h"
#include "semantic_edge_vo/common/class_table.h"
#include "semantic_edge_vo/fields/nearest_neighbor_field.h"
#include "semantic_edge_vo/backend/odometry.h"
#include "semantic_edge_vo/frontend/point_sampler.h"
#include "semantic_edge_vo/config/parameter_loader.h"

namespace semantic_edge_vo {

// Each loader reads one options struct from a parameter source (a nodelet's private parameters or
// a section of a YAML file; names as in config/semantic_edge_vo.yaml and the README) and returns
// the validation error, empty when the options are usable.
std::string loadCannyOptions(ParameterLoader* loader, CannyOptions* options);
std::string loadPointSamplerOptions(ParameterLoader* loader, PointSamplerOptions* options);
std::string loadFieldOptions(ParameterLoader* loader, FieldOptions* options);
std::string loadOdometryOptions(ParameterLoader* loader, OdometryOptions* options);
/// Reads the class table from `classes` (a list of {name, id, rgb: [r, g, b]}); Cityscapes when absent.
std::string loadClassTable(ParameterLoader* loader, ClassTable* table);

}  // namespace semantic_edge_vo
