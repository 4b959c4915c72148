#pragma once
// Shared by the cost functors: a keyframe pose as Ceres parameters, camera-to-world rotation as an
// Eigen quaternion (x, y, z, w) and translation (3), and the projection of a host point into a target.
#include <Eigen/Geometry>

namespace semantic_edge_vo {
namespace factors {

/// The point at host pixel (u, v) and inverse depth `rho`, seen from the target camera: returns it
/// in the target optical frame (unnormalised: z may be any sign).
template <typename T>
Eigen::Matrix<T, 3, 1> hostToTarget(const T* q_world_host, const T* t_world_host, const T* q_world_target,
                                    const T* t_world_target, const T& rho, const Eigen::Vector3d& host_ray) {
  const Eigen::Map<const Eigen::Quaternion<T>> q_h(q_world_host), q_t(q_world_target);
  const Eigen::Map<const Eigen::Matrix<T, 3, 1>> p_h(t_world_host), p_t(t_world_target);
  // Homogeneous in the inverse depth: world point * rho = R_h ray + rho p_h; bring it to the target.
  const Eigen::Matrix<T, 3, 1> scaled_world = q_h * host_ray.cast<T>() + rho * p_h;
  return q_t.conjugate() * (scaled_world - rho * p_t);
}

}  // namespace factors
}  // namespace semantic_edge_vo
