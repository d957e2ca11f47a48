#include "assembly/dof_map.hpp"

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

Eigen::VectorXd DofMap::restrict(const Eigen::VectorXd& global) const {
  Eigen::VectorXd r(num_free_);
  for (int i = 0; i < num_free_; ++i) r[i] = global[free_dofs_[i]];
  return r;
}

void DofMap::add_free(const Eigen::VectorXd& free_values, Eigen::VectorXd& global) const {
  for (int i = 0; i < num_free_; ++i) global[free_dofs_[i]] += free_values[i];
}

}  // namespace hofem
