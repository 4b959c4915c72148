#pragma once
#include <ceres/ceres.h>

namespace semantic_edge_vo {
namespace factors {

/// Regulariser of an inverse depth (paper III-C: penalises large updates, since an edge point's depth
/// can be unobservable): (rho - prior) / sigma.
class InverseDepthPrior {
 public:
  InverseDepthPrior(double prior, double sigma) : prior_(prior), sigma_(sigma) {}

  template <typename T>
  bool operator()(const T* rho, T* residual) const {
    residual[0] = (rho[0] - prior_) / sigma_;
    return true;
  }

  static ceres::CostFunction* Create(double prior, double sigma) {
    return new ceres::AutoDiffCostFunction<InverseDepthPrior, 1, 1>(new InverseDepthPrior(prior, sigma));
  }

 private:
  double prior_, sigma_;
};

}  // namespace factors
}  // namespace semantic_edge_vo
