#include "assembly/sparsity_pattern.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <limits>

namespace hofem {

namespace {

// Greedy colouring on shared vertices (two elements sharing any node share a
// vertex of it, for tets and hexes): each element takes the smallest colour not
// used by an element already coloured that touches one of its vertices.
std::vector<std::vector<int>> colour_elements(const Mesh& mesh) {
  const int nv = mesh.vertices_per_element();
  std::vector<std::vector<int>> elements_of_node(mesh.num_nodes());
  for (int e = 0; e < mesh.num_elements(); ++e)
    for (int v = 0; v < nv; ++v) elements_of_node[mesh.elements(v, e)].push_back(e);
  std::vector<int> colour(mesh.num_elements(), -1);
  std::vector<char> used;
  int ncolours = 0;
  for (int e = 0; e < mesh.num_elements(); ++e) {
    used.assign(ncolours + 1, 0);
    for (int v = 0; v < nv; ++v)
      for (int other : elements_of_node[mesh.elements(v, e)])
        if (colour[other] >= 0) used[colour[other]] = 1;
    int c = 0;
    while (used[c]) ++c;
    colour[e] = c;
    ncolours = std::max(ncolours, c + 1);
  }
  std::vector<std::vector<int>> groups(ncolours);
  for (int e = 0; e < mesh.num_elements(); ++e) groups[colour[e]].push_back(e);
  return groups;
}

}  // namespace

SparsityPattern::SparsityPattern(const Mesh& mesh, const DofMap& dofs) {
  const int n = mesh.nodes_per_element();
  block_dim_ = 3 * n;
  block_size_ = static_cast<size_t>(block_dim_) * block_dim_;
  const int nf = dofs.num_free();

  // Column structure: free DOFs coupled through an element (node-level
  // adjacency expanded to the three components).
  std::vector<std::vector<int>> node_neighbours(mesh.num_nodes());
  for (int e = 0; e < mesh.num_elements(); ++e)
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) node_neighbours[mesh.elements(i, e)].push_back(mesh.elements(j, e));
  std::vector<std::int64_t> col_ptr(nf + 1, 0);
  std::vector<std::int64_t> row_idx;
  for (int node = 0; node < mesh.num_nodes(); ++node) {
    auto& nb = node_neighbours[node];
    std::sort(nb.begin(), nb.end());
    nb.erase(std::unique(nb.begin(), nb.end()), nb.end());
  }
  for (int c = 0; c < nf; ++c) {
    const int dof = dofs.free_dofs()[c];
    for (int other : node_neighbours[dof / 3])
      for (int k = 0; k < 3; ++k)
        if (const int r = dofs.free_index(3 * other + k); r >= 0) row_idx.push_back(r);
    col_ptr[c + 1] = static_cast<std::int64_t>(row_idx.size());
  }
  // Rows within a column are sorted: neighbours sorted, components ascending,
  // and free indices increase with global DOF.
  pattern_.resize(nf, nf);
  pattern_.resizeNonZeros(static_cast<Eigen::Index>(row_idx.size()));
  std::copy(col_ptr.begin(), col_ptr.end(), pattern_.outerIndexPtr());
  std::copy(row_idx.begin(), row_idx.end(), pattern_.innerIndexPtr());
  std::fill(pattern_.valuePtr(), pattern_.valuePtr() + row_idx.size(), 0.0);
  if (row_idx.size() > static_cast<size_t>(std::numeric_limits<int>::max()))
    throw std::length_error(fmt::format("sparsity pattern: {} nonzeros exceed the 32-bit element map", row_idx.size()));

  // Element-to-nonzero map by binary search in each column (done once).
  map_.assign(block_size_ * mesh.num_elements(), -1);
  std::vector<int> edofs(block_dim_);
  for (int e = 0; e < mesh.num_elements(); ++e) {
    for (int i = 0; i < n; ++i)
      for (int a = 0; a < 3; ++a) edofs[3 * i + a] = dofs.free_index(3 * mesh.elements(i, e) + a);
    int* m = map_.data() + static_cast<size_t>(e) * block_size_;
    for (int r = 0; r < block_dim_; ++r) {
      if (edofs[r] < 0) continue;
      for (int c = 0; c < block_dim_; ++c) {
        if (edofs[c] < 0) continue;
        const std::int64_t* begin = row_idx.data() + col_ptr[edofs[c]];
        const std::int64_t* end = row_idx.data() + col_ptr[edofs[c] + 1];
        const std::int64_t* it = std::lower_bound(begin, end, static_cast<std::int64_t>(edofs[r]));
        m[static_cast<size_t>(r) * block_dim_ + c] = static_cast<int>(it - row_idx.data());
      }
    }
  }
  colours_ = colour_elements(mesh);
}

}  // namespace hofem
