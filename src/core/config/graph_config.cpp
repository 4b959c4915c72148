#include "semantic_edge_vo/config/graph_config.h"

#include <algorithm>
#include <array>

#include "semantic_edge_vo/config/intake_options_loading.h"
#include "semantic_edge_vo/config/options_loading.h"
#include "semantic_edge_vo/config/yaml_parameter_source.h"

namespace semantic_edge_vo {
namespace {

const std::array<const char*, 5> kBlocks = {"edge_intake", "segmenter", "nearest_neighbor_field", "tracking", "mapping"};

/// The first of `errors` that is not empty.
std::string firstError(std::initializer_list<std::string> errors) {
  for (const std::string& error : errors)
    if (!error.empty()) return error;
  return "";
}

}  // namespace

std::string loadGraphConfig(const std::string& path, GraphConfig* config) {
  const YamlParameterSource file(path);
  if (!file.error().empty()) return file.error();
  for (const std::string& name : file.names()) {
    const std::string block = name.substr(0, name.find('/'));
    if (std::find(kBlocks.begin(), kBlocks.end(), block) == kBlocks.end())
      return file.resolve(block) + ": unknown block (edge_intake, segmenter, nearest_neighbor_field, tracking or mapping)";
  }
  const YamlParameterSource intake = file.section("edge_intake"), segmenter = file.section("segmenter"),
                            field = file.section("nearest_neighbor_field"), tracking = file.section("tracking"),
                            mapping = file.section("mapping");
  ParameterLoader intake_loader(intake), segmenter_loader(segmenter), field_loader(field), tracking_loader(tracking),
      mapping_loader(mapping);
  ClassTable segmenter_classes, mapping_classes;  // each nodelet reads its own copy of the table
  tracking_loader.load("use_edges", &config->frame.use_field);
  std::string error = firstError({loadIntakeStreamOptions(&intake_loader, &config->intake_stream),
                                  loadSemanticEdgeOptions(&intake_loader, &config->frame.intake),
                                  loadPointSamplerOptions(&intake_loader, &config->frame.sampler),
                                  loadClassTable(&intake_loader, &config->classes),
                                  loadSegmenterOptions(&segmenter_loader, &config->segmenter),
                                  loadSegmenterOutputOptions(&segmenter_loader, &config->segmenter_output),
                                  loadClassTable(&segmenter_loader, &segmenter_classes),
                                  loadFieldOptions(&field_loader, &config->frame.field),
                                  loadTfOptions(&tracking_loader, &config->tf),
                                  loadLiveMappingOptions(&tracking_loader, &config->live_mapping),
                                  loadOdometryOptions(&tracking_loader, &config->odometry),
                                  loadMapOutputOptions(&mapping_loader, &config->map_output),
                                  loadClassTable(&mapping_loader, &mapping_classes)});
  const std::array<const ParameterSource*, 5> sources = {&intake, &segmenter, &field, &tracking, &mapping};
  const std::array<const ParameterLoader*, 5> loaders = {&intake_loader, &segmenter_loader, &field_loader, &tracking_loader,
                                                         &mapping_loader};
  config->summary.clear();
  config->changed_from_defaults.clear();
  for (std::size_t b = 0; b < kBlocks.size(); ++b) {
    if (error.empty()) error = sources[b]->error();
    if (const std::string unknown = loaders[b]->unknownNames(); error.empty() && !unknown.empty())
      error = "unknown parameter (no option has this name): " + unknown;
    config->summary += loaders[b]->summary();
    for (const std::string& changed : loaders[b]->changedFromDefaults())
      config->changed_from_defaults.push_back(std::string(kBlocks[b]) + "/" + changed);
  }
  return error;
}

}  // namespace semantic_edge_vo
