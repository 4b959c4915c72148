#include "semantic_edge_vo/config/intake_options_loading.h"

#include <vector>

#include "semantic_edge_vo/config/options_loading.h"

namespace semantic_edge_vo {

std::string loadSemanticEdgeOptions(ParameterLoader* loader, SemanticEdgeOptions* options) {
  std::string mode = toString(options->mode);
  loader->load("mode", &mode, "(canny | fused | semantic_edges)");
  if (!parseIntakeMode(mode, &options->mode)) return "mode must be canny, fused or semantic_edges (got '" + mode + "')";
  loader->load("class_threshold", &options->class_threshold, "probability");
  loader->load("side_distance", &options->side_distance, "px");
  loader->load("edges/threshold", &options->thinning.threshold, "probability");
  loader->load("edges/blur_sigma", &options->thinning.blur_sigma, "px");
  const std::string canny_error = loadCannyOptions(loader, &options->canny);
  options->thinning.border = options->canny.border;
  return canny_error.empty() ? options->validate() : canny_error;
}

std::string loadSegmenterOptions(ParameterLoader* loader, SegmenterOptions* options) {
  loader->load("model_path", &options->model_path, "(file)");
  loader->load("config_path", &options->config_path, "(file; caffe, tensorflow, darknet)");
  loader->load("format", &options->format, "(torch | onnx | caffe | tensorflow | darknet)");
  loader->load("input_width", &options->input_width, "px");
  loader->load("input_height", &options->input_height, "px");
  loader->load("scale", &options->scale, "per gray level");
  loader->load("swap_rb", &options->swap_rb);
  std::vector<double> mean(options->mean.begin(), options->mean.end());
  loader->load("mean", &mean, "gray levels (B, G, R)");
  if (mean.size() != 3) return "mean must list 3 values (B, G, R gray levels)";
  std::copy(mean.begin(), mean.end(), options->mean.begin());
  loader->load("output_channels", &options->output_channels, "(empty: class c reads output c + 1)");
  loader->load("backend", &options->backend, "(cpu | cuda | opencl)");
  return options->validate();
}

}  // namespace semantic_edge_vo
