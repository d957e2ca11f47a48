#pragma once
// A rigid floor: the half-space n . x >= height. Every node below it is pushed
// back by a quadratic penalty energy 1/2 k d^2 (d = height - n . x > 0), the
// same term for explicit integrators (as the force k d n) and inside the
// incremental potential of the implicit ones (with Hessian k n n^T).
//
// Why a penalty and not a barrier (IPC's log barrier): the penalty is C^1 with a
// piecewise-constant Hessian, adds no line-search filtering and works unchanged
// for explicit schemes; its price is a penetration of |f|/k, which the stats
// report (max penetration) and the scene's stiffness controls. A barrier would
// guarantee zero penetration but needs step-size filtering in Newton and is
// unusable in explicit schemes. Contact is nodal (every node of a higher-order
// element, edge and face nodes included), no friction.
#include "assembly/dof_map.hpp"
#include "linalg/sparse_matrix.hpp"

#include <Eigen/Core>

#include <vector>

namespace hofem {

struct Floor {
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  ///< unit normal pointing into the allowed side
  double height = 0.0;                                ///< n . x >= height is allowed
  double stiffness = 0.0;                             ///< penalty k per node (force / length)

  /// Penetration depth of position p (> 0 below the floor).
  double depth(const Eigen::Vector3d& p) const { return height - normal.dot(p); }
  // `only`: the nodes to count (a distributed run's owned nodes, so that each
  // node's term enters the sums over ranks once); null: every node.
  /// Sum over nodes of 1/2 k d^2 (x: 3 per node).
  double energy(const Eigen::VectorXd& x, const std::vector<char>* only = nullptr) const;
  /// Adds the penalty forces k d n to f (all DOFs); returns the number of nodes in contact.
  int add_forces(const Eigen::VectorXd& x, Eigen::VectorXd& f, const std::vector<char>* only = nullptr) const;
  /// Adds k n n^T of every node in contact to K over the free DOFs (K's pattern
  /// has every node's 3x3 block).
  void add_hessian(const Eigen::VectorXd& x, const DofMap& dofs, SparseMatrix& K,
                   const std::vector<char>* only = nullptr) const;
  /// Largest penetration depth over the nodes (0 if none).
  double max_depth(const Eigen::VectorXd& x) const;
  /// Nodes in contact.
  int contacts(const Eigen::VectorXd& x, const std::vector<char>* only = nullptr) const;
};

}  // namespace hofem
