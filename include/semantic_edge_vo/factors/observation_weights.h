#pragma once

namespace semantic_edge_vo {
namespace factors {

/// Sigmas and Huber thresholds of the window's point observation rows (WindowObservations).
struct ObservationWeights {
  double photometric_sigma = 4.0, photometric_huber = 9.0;  ///< gray levels/px (gradient magnitude)
  double edge_sigma = 1.0, edge_huber = 1.5;                ///< px
  double edge_weight = 0.5;                                 ///< the edge row's cost is scaled by this
};

}  // namespace factors
}  // namespace semantic_edge_vo
