#pragma once
#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include "semantic_edge_vo/common/array_view.h"
#include "semantic_edge_vo/common/edge_set.h"

namespace semantic_edge_vo {

/// Which edges a lookup may match (paper III-B).
enum class FieldKind {
  kAnnf,  ///< one field for all edges
  kOnnf,  ///< one field per gradient-direction bin
  kSnnf,  ///< one field per semantic class; an edge with several classes is in each of their fields.
          ///< With more than one class, one more layer holds every edge (what a class the drive
          ///< cannot rely on is matched in: see ClassReliability)
};
const char* toString(FieldKind kind);
/// Parses "annf" | "onnf" | "snnf"; false on anything else.
bool parseFieldKind(const std::string& text, FieldKind* kind);

struct FieldOptions {
  FieldKind kind = FieldKind::kSnnf;
  int pyramid_levels = 4;        ///< level 0 is full resolution, each next level halves it
  int orientation_bins = 8;      ///< ONNF bins over 360 degrees of gradient direction
  float truncation_radius = 8.0f;   ///< lookups farther than this find nothing, pixels of the queried level (coarse levels reach far)
  int cell_size = 4;             ///< bucket side at levels 0 and 1, px (4: fastest lookups, see benchmark_fields); halved at each level from 2 on, down to 2

  std::string validate() const;
};

/// The nearest seed of a layer to a query point.
struct FieldMatch {
  float u = 0, v = 0;                ///< seed position, pixels of the queried level
  float normal_x = 0, normal_y = 0;  ///< seed's unit gradient direction
  float distance = 0;                ///< Euclidean distance from the query, pixels of the level
  std::uint32_t edge = 0;            ///< index of the seed's edge pixel in the frame's EdgeSet
};

/// Bucket index of one pyramid level (owned arrays; layout of NearestNeighborFieldLevel.msg).
struct FieldLevelData {
  float scale = 1.0f;
  int width = 0, height = 0;
  int cell_size = 8, grid_cols = 0, grid_rows = 0;
  std::vector<float> seed_u, seed_v, seed_normal_x, seed_normal_y;
  std::vector<std::uint32_t> seed_edge;
  std::vector<std::uint32_t> cell_start;  ///< num_layers * cells + 1
  std::vector<std::uint32_t> entry_seed;
};

/// Read-only view of one level; answers exact nearest-neighbour queries.
struct FieldLevelView {
  float scale = 1.0f;
  int width = 0, height = 0;
  int cell_size = 8, grid_cols = 0, grid_rows = 0;
  ArrayView<float> seed_u, seed_v, seed_normal_x, seed_normal_y;
  ArrayView<std::uint32_t> seed_edge;
  ArrayView<std::uint32_t> cell_start;
  ArrayView<std::uint32_t> entry_seed;

  /// Exact nearest seed of `layer` to (x, y) (level pixels) within `max_radius`; false if none.
  bool nearest(int layer, float x, float y, float max_radius, FieldMatch* match) const;
  /// Is any seed of `layer` within `radius` of (x, y)? The same answer as nearest() with that
  /// radius, cheaper: it scans only the buckets the disc touches and stops at the first seed in it.
  bool anyWithin(int layer, float x, float y, float radius) const;
  /// Empty when the arrays are consistent with each other and with `num_layers`, else what is wrong.
  std::string validate(int num_layers) const;
};

class NearestNeighborFieldView;

/// All levels of a field, owned: what the builder makes.
struct NearestNeighborFieldData {
  FieldKind kind = FieldKind::kSnnf;
  int num_layers = 0;
  int orientation_bins = 0;
  int all_edges_layer = -1;  ///< the layer holding every edge (ANNF: 0; SNNF: after the classes); -1: none (ONNF)
  std::vector<std::string> layer_names;
  float truncation_radius = 0.0f;
  std::vector<FieldLevelData> levels;

  NearestNeighborFieldView view() const;
};

/// All levels of a field, owned elsewhere (NearestNeighborFieldData or a message).
class NearestNeighborFieldView {
 public:
  FieldKind kind = FieldKind::kSnnf;
  int num_layers = 0;
  int orientation_bins = 0;
  int all_edges_layer = -1;  ///< the layer holding every edge; -1: none
  float truncation_radius = 0.0f;
  std::vector<FieldLevelView> levels;

  /// Nearest seed of `layer` at `level`, within the truncation radius.
  bool nearest(int level, int layer, float x, float y, FieldMatch* match) const {
    return levels[static_cast<std::size_t>(level)].nearest(layer, x, y, truncation_radius, match);
  }
  /// ... within `radius` (at most the truncation radius): a small radius makes the lookup cheap.
  bool nearestWithin(int level, int layer, float x, float y, float radius, FieldMatch* match) const {
    return levels[static_cast<std::size_t>(level)].nearest(layer, x, y, std::min(radius, truncation_radius), match);
  }
  /// ONNF layer of a gradient direction (any length).
  int orientationBin(float normal_x, float normal_y) const;
  /// Empty when usable, otherwise what is wrong.
  std::string validate() const;
};

/// Level coordinate of a full-resolution coordinate (pixel centres map to pixel centres).
inline float toLevel(float full, float scale) { return scale * (full + 0.5f) - 0.5f; }
inline float toFull(float level, float scale) { return (level + 0.5f) / scale - 0.5f; }

/// Builds every level of the field over all `edges` of a width x height image.
/// @param[in] class_names the class table: SNNF layers (and, with more than one class, the all-edges
///            layer after them); ignored by ANNF and ONNF
NearestNeighborFieldData buildNearestNeighborField(const EdgeSetView& edges, int width, int height,
                                                   const std::vector<std::string>& class_names,
                                                   const FieldOptions& options);

}  // namespace semantic_edge_vo
