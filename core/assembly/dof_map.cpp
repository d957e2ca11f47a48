#include "assembly/dof_map.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <stdexcept>

namespace hofem {

namespace {
std::atomic<std::uint64_t> last_identity{0};
}  // namespace

DofMap::DofMap(int num_nodes, const std::vector<int>& constrained_nodes)
    : free_index_(3 * num_nodes, 0), identity_(++last_identity) {
  for (int n : constrained_nodes) {
    if (n < 0 || n >= num_nodes) throw std::out_of_range("DofMap: constrained node " + std::to_string(n) + " out of range");
    for (int c = 0; c < 3; ++c) free_index_[3 * n + c] = -1;
  }
  for (int d = 0; d < 3 * num_nodes; ++d) {
    if (free_index_[d] == -1) {
      constrained_dofs_.push_back(d);
      continue;
    }
    free_index_[d] = num_free_++;
    free_dofs_.push_back(d);
  }
}

std::vector<int> node_set_union(const std::vector<std::vector<int>>& sets, int num_nodes, std::string_view what,
                                bool disjoint) {
  std::vector<int> set_of(static_cast<size_t>(std::max(num_nodes, 0)), -1);  // per node: the first set holding it
  std::vector<int> nodes;
  for (size_t k = 0; k < sets.size(); ++k)
    for (int n : sets[k]) {
      if (n < 0 || n >= num_nodes)
        throw std::invalid_argument(
            fmt::format("{} {}: node {} is out of range (the mesh has {} nodes)", what, k, n, num_nodes));
      if (set_of[n] == -1) {
        set_of[n] = static_cast<int>(k);
        nodes.push_back(n);
      } else if (disjoint && set_of[n] != static_cast<int>(k)) {
        throw std::invalid_argument(fmt::format("{} {}: node {} is already in {} {}", what, k, n, what, set_of[n]));
      }
    }
  std::sort(nodes.begin(), nodes.end());
  return nodes;
}

Eigen::VectorXd DofMap::restrict(const Eigen::VectorXd& global) const {
  Eigen::VectorXd r(num_free_);
  for (int i = 0; i < num_free_; ++i) r[i] = global[free_dofs_[i]];
  return r;
}

void DofMap::add_free(const Eigen::VectorXd& free_values, Eigen::VectorXd& global) const {
  for (int i = 0; i < num_free_; ++i) global[free_dofs_[i]] += free_values[i];
}

}  // namespace hofem
