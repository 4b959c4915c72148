#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "semantic_edge_vo/synthetic/semantic_channels.h"

namespace semantic_edge_vo {
namespace synthetic {

/// Errors a real semantic edge network makes, each with a strength in [0, 1] (0: none).
struct NetworkNoiseOptions {
  /// Blobs (about 50 px) where the label flips to a confusable class (road-sidewalk, car-truck...):
  /// class probabilities and edge labels. Strength 1 affects roughly half the image.
  double label_confusion = 0.0;
  /// Thick, blurred edges: a dilation by 2 x strength px, then a Gaussian of 1.5 x strength px.
  double edge_blur = 0.0;
  /// Missed edges: edge pixels removed in blobs; about this fraction of them.
  double missed_edges = 0.0;
  /// Spurious edges: curvy false edge fragments (labelled with the local class) in patches that cover
  /// up to this fraction of the image.
  double spurious_edges = 0.0;

  bool any() const { return label_confusion > 0.0 || edge_blur > 0.0 || missed_edges > 0.0 || spurious_edges > 0.0; }
  std::string validate() const;
};

/// Reads a command-line noise flag (--label-confusion, --edge-blur, --missed-edges, --spurious-edges)
/// into `options`; false when `flag` is not one of them. A value that is not a number leaves the
/// option as it was and says so in `error`.
bool parseNoiseFlag(const std::string& flag, const std::string& value, NetworkNoiseOptions* options, std::string* error);
/// The flags parseNoiseFlag reads.
const std::vector<std::string>& noiseFlags();

/// Applies the noise models in place, deterministically for the seed.
void applyNetworkNoise(const NetworkNoiseOptions& options, std::uint64_t seed, SemanticNetworkOutput* output);

}  // namespace synthetic
}  // namespace semantic_edge_vo
