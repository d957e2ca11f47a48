#include "assembly/sparsity_pattern.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <limits>

namespace hofem {

namespace {

// Greedy colouring on shared vertices (two elements sharing any node share a
// vertex of it, for tets and hexes): each element takes the smallest colour not
// used by an element already coloured that touches one of its vertices.
// start/elements_of_node: the elements of every node (CSR).
std::vector<std::vector<int>> colour_elements(const Mesh& mesh, const std::vector<int>& start,
                                              const std::vector<int>& elements_of_node) {
  const int nv = mesh.vertices_per_element();
  std::vector<int> colour(mesh.num_elements(), -1);
  std::vector<char> used;
  int ncolours = 0;
  for (int e = 0; e < mesh.num_elements(); ++e) {
    used.assign(ncolours + 1, 0);
    for (int v = 0; v < nv; ++v) {
      const int node = mesh.elements(v, e);
      for (int q = start[node]; q < start[node + 1]; ++q)
        if (const int c = colour[elements_of_node[q]]; c >= 0) used[c] = 1;
    }
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

// Everything per node, then expanded to the three components: a free node
// couples to the same free neighbours in all its columns, and a neighbour's three
// rows are consecutive in each (free indices follow global DOF order). So column
// 3k + b of free node k holds, for each free neighbour m (ascending), the rows
// 3m', 3m' + 1, 3m' + 2, and an element entry (row of node i comp a, column of
// node j comp b) sits at col_start(j, 0) + b * column_length(j) + 3 * (rank of i
// among j's free neighbours) + a: one search per node pair, and one stored
// position per node pair. Every array is written first on the threads that use
// it (page faults of ~100 MB arrays are a large share of a serial pass).
SparsityPattern::SparsityPattern(const Mesh& mesh, const DofMap& dofs) {
  const int n = mesh.nodes_per_element(), nn = mesh.num_nodes(), ne = mesh.num_elements();
  nodes_ = n;
  block_size_ = static_cast<size_t>(n) * n;
  const int nf = dofs.num_free();
  const bool parallel = ne >= 512;
  auto free_node = [&](int node) { return dofs.free_index(3 * node) >= 0; };

  // Elements of each node (CSR).
  std::vector<int> start(static_cast<size_t>(nn) + 1, 0), elements_of_node(static_cast<size_t>(ne) * n);
  for (int e = 0; e < ne; ++e)
    for (int i = 0; i < n; ++i) ++start[mesh.elements(i, e) + 1];
  for (int k = 0; k < nn; ++k) start[k + 1] += start[k];
  {
    std::vector<int> fill(start.begin(), start.end() - 1);
    for (int e = 0; e < ne; ++e)
      for (int i = 0; i < n; ++i) elements_of_node[fill[mesh.elements(i, e)]++] = e;
  }
  // Free neighbours of every free node, ascending (constrained nodes have no rows).
  std::vector<std::vector<int>> neighbours(static_cast<size_t>(nn));
#pragma omp parallel for schedule(dynamic, 256) if (parallel)
  for (int k = 0; k < nn; ++k) {
    if (!free_node(k)) continue;
    std::vector<int>& nb = neighbours[k];
    nb.reserve(static_cast<size_t>(start[k + 1] - start[k]) * n);
    for (int q = start[k]; q < start[k + 1]; ++q)
      for (int i = 0; i < n; ++i)
        if (const int m = mesh.elements(i, elements_of_node[q]); free_node(m)) nb.push_back(m);
    std::sort(nb.begin(), nb.end());
    nb.erase(std::unique(nb.begin(), nb.end()), nb.end());
  }
  column_length_.assign(static_cast<size_t>(nn), 0);
  for (int k = 0; k < nn; ++k) column_length_[k] = 3 * static_cast<int>(neighbours[k].size());
  first_element_.assign(static_cast<size_t>(nn), ne);  // ne: a node of no element
  for (int k = 0; k < nn; ++k)
    if (start[k + 1] > start[k]) first_element_[k] = elements_of_node[start[k]];  // filled in element order
  // Columns: free DOF c = 3 * free node + b.
  std::vector<std::int64_t> col_ptr(static_cast<size_t>(nf) + 1, 0);
  for (int c = 0; c < nf; ++c) col_ptr[c + 1] = col_ptr[c] + column_length_[dofs.free_dofs()[c] / 3];
  const std::int64_t nnz = col_ptr[nf];
  if (nnz > static_cast<std::int64_t>(std::numeric_limits<int>::max()))
    throw std::length_error(fmt::format("sparsity pattern: {} nonzeros exceed the 32-bit element map", nnz));
  column_start_ = std::move(col_ptr);
  row_.resize(static_cast<size_t>(nnz));  // uninitialised: filled below, on the threads that read it later
#pragma omp parallel for schedule(static) if (parallel)
  for (int c = 0; c < nf; ++c) {
    std::int64_t q = column_start_[c];
    for (int m : neighbours[dofs.free_dofs()[c] / 3])
      for (int a = 0; a < 3; ++a) row_[q++] = dofs.free_index(3 * m + a);
  }

  // Node-pair map (done once).
  map_.resize(block_size_ * static_cast<size_t>(ne));
#pragma omp parallel for schedule(static) if (parallel)
  for (int e = 0; e < ne; ++e) {
    int* m = map_.data() + static_cast<size_t>(e) * block_size_;
    for (int j = 0; j < n; ++j) {
      const int node_j = mesh.elements(j, e);
      int* mj = m + static_cast<size_t>(j) * n;
      if (!free_node(node_j)) {
        std::fill(mj, mj + n, -1);
        continue;
      }
      const std::vector<int>& nb = neighbours[node_j];
      const std::int64_t first = column_start_[dofs.free_index(3 * node_j)];
      for (int i = 0; i < n; ++i) {
        const int node_i = mesh.elements(i, e);
        mj[i] = free_node(node_i)
                    ? static_cast<int>(first + 3 * (std::lower_bound(nb.begin(), nb.end(), node_i) - nb.begin()))
                    : -1;
      }
    }
  }
  colours_ = colour_elements(mesh, start, elements_of_node);
}

SparseMatrix SparsityPattern::zero_matrix() const {
  SparseMatrix K;
  shape(K);
  return K;
}

void SparsityPattern::shape(SparseMatrix& K) const {
  const Eigen::Index n = size();
  const std::int64_t nnz = nonzeros();
  K.resize(n, n);
  K.resizeNonZeros(nnz);  // uninitialised arrays: the loops below touch them first
  std::copy(column_start_.begin(), column_start_.end(), K.outerIndexPtr());
  const std::int32_t* rows = row_.data();
  auto* k_inner = K.innerIndexPtr();
  double* values = K.valuePtr();
#pragma omp parallel for schedule(static)
  for (std::int64_t q = 0; q < nnz; ++q) {
    k_inner[q] = rows[q];
    values[q] = 0.0;
  }
}

void SparsityPattern::zero_values(SparseMatrix& K) const {
  double* values = K.valuePtr();
  const std::int64_t nnz = K.nonZeros();
#pragma omp parallel for schedule(static)
  for (std::int64_t q = 0; q < nnz; ++q) values[q] = 0.0;
}

}  // namespace hofem
