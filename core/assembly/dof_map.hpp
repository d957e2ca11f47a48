#pragma once
// Degrees of freedom: three per node (x, y, z displacement/position components),
// global index 3 * node + component. Dirichlet conditions are imposed by
// elimination: constrained DOFs keep prescribed values and are left out of the
// free numbering that gradients and Hessians use.
#include <Eigen/Core>

#include <cstdint>
#include <string_view>
#include <vector>

namespace hofem {

class DofMap {
 public:
  DofMap() = default;
  /// All DOFs of the given nodes are constrained (all three components).
  DofMap(int num_nodes, const std::vector<int>& constrained_nodes);

  int num_dofs() const { return static_cast<int>(free_index_.size()); }
  int num_free() const { return num_free_; }
  /// Free index of a global DOF, or -1 if constrained.
  int free_index(int dof) const { return free_index_[dof]; }
  const std::vector<int>& free_index() const { return free_index_; }
  /// Global DOF of each free index.
  const std::vector<int>& free_dofs() const { return free_dofs_; }
  const std::vector<int>& constrained_dofs() const { return constrained_dofs_; }
  /// A number no other DOF map built in this process has (0: default-constructed).
  /// A DOF map never changes after construction, so copies share it; caches of
  /// what was built for a DOF map (the p-multigrid's hierarchy) key on it, since
  /// an address is reused when a problem rebuilds its map in place (a released
  /// node set) or a new problem is constructed where an old one was.
  std::uint64_t identity() const { return identity_; }

  /// Restriction of a global vector to the free DOFs, and the reverse scatter.
  Eigen::VectorXd restrict(const Eigen::VectorXd& global) const;
  void add_free(const Eigen::VectorXd& free_values, Eigen::VectorXd& global) const;

 private:
  std::vector<int> free_index_;
  std::vector<int> free_dofs_;
  std::vector<int> constrained_dofs_;
  int num_free_ = 0;
  std::uint64_t identity_ = 0;
};

/// The union of node sets given on a mesh of `num_nodes` nodes, sorted and each
/// node once, every id checked: one out of range is std::invalid_argument
/// "<what> <k>: node <n> is out of range (the mesh has <num_nodes> nodes)"; with
/// `disjoint`, so is a node in two sets ("<what> <k>: node <n> is already in
/// <what> <j>"). The constrained nodes of the static and dynamic problems.
std::vector<int> node_set_union(const std::vector<std::vector<int>>& sets, int num_nodes, std::string_view what,
                                bool disjoint);

}  // namespace hofem
