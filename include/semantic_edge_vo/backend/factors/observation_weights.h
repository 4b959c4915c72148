#pragma once

namespace semantic_edge_vo {
namespace factors {

/// Sigmas and Huber thresholds of the window's point observation rows (WindowObservations), taken
/// from WindowOptimizerOptions::observationWeights(), where their defaults are.
struct ObservationWeights {
  double photometric_sigma, photometric_huber;  ///< gray levels/px (gradient magnitude)
  double edge_sigma, edge_huber;                ///< px
  double edge_weight;                           ///< the edge row's cost is scaled by this
};

}  // namespace factors
}  // namespace semantic_edge_vo
