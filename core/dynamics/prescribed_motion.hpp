#pragma once
// Prescribed motion of node sets over time: fixed nodes, translation, rotation
// about an axis (twisting, compressing). A motion maps a node's reference
// position X to its position x(X, t); velocity and acceleration come from the
// closed forms below, so the boundary is exact at every stage of every
// integrator.
#include <Eigen/Core>

#include <functional>
#include <limits>
#include <vector>

namespace hofem {

struct PrescribedMotion {
  std::vector<int> nodes;
  /// x(X, t); empty means fixed at X.
  std::function<Eigen::Vector3d(const Eigen::Vector3d& X, double t)> position;
  /// dx/dt and d2x/dt2 at (X, t); empty means zero.
  std::function<Eigen::Vector3d(const Eigen::Vector3d& X, double t)> velocity, acceleration;
  /// From this time on the nodes are free (a slingshot's release); infinity: never.
  double release = std::numeric_limits<double>::infinity();
  bool moves() const { return static_cast<bool>(position); }
};

/// The nodes stay at their reference positions.
PrescribedMotion fixed_nodes(std::vector<int> nodes);
/// x = X + v t (constant velocity v) for t <= until, then at rest.
PrescribedMotion translation(std::vector<int> nodes, const Eigen::Vector3d& velocity, double until);
/// Rotation about the axis through `point` with direction `axis` at angular
/// velocity omega (rad/s), the axis itself moving at `velocity` (a screw motion:
/// twist and compress at once), for t <= until, then at rest:
/// x = c + v t + R(omega t)(X - c).
PrescribedMotion rotation(std::vector<int> nodes, const Eigen::Vector3d& point, const Eigen::Vector3d& axis,
                          double omega, double until, const Eigen::Vector3d& velocity = Eigen::Vector3d::Zero());

}  // namespace hofem
