#pragma once
// The sparsity pattern of an element-assembled matrix over the free DOFs,
// computed once per (mesh, DofMap), with
//  - an element-to-nonzero map at node level: for each element and node pair
//    (i, j) the position in the matrix's value array of entry (3i, 3j) of its
//    (3n x 3n) block (-1 where node i or j is constrained); the other eight
//    entries of the 3x3 block follow from the column length of node j (below),
//    so re-assembly only writes values. Per node pair rather than per entry:
//    9x less memory (Tet20 at 10k elements: 16 MB instead of 150 MB) and 9x
//    fewer index loads in the scatter;
//  - an element colouring: elements of one colour share no node, so one colour
//    is assembled in parallel without atomics, in a fixed order (results are
//    bitwise reproducible whatever the thread count).
#include "assembly/dof_map.hpp"
#include "linalg/sparse_matrix.hpp"
#include "mesh/mesh.hpp"

#include <utility>
#include <vector>

namespace hofem {

class SparsityPattern {
 public:
  SparsityPattern(const Mesh& mesh, const DofMap& dofs);

  /// A matrix with this pattern and all values zero (compressed).
  SparseMatrix zero_matrix() const;
  /// Free DOFs (rows and columns of the matrix).
  Eigen::Index size() const { return static_cast<Eigen::Index>(column_start_.size()) - 1; }
  /// Gives K this pattern with all values zero, like K = zero_matrix() but
  /// filling the index and value arrays on every thread: the first touch of a
  /// ~100 MB array is page faults, which a serial copy takes one at a time.
  void shape(SparseMatrix& K) const;
  /// Sets every value of a matrix of this pattern to zero (in parallel).
  void zero_values(SparseMatrix& K) const;
  /// Node-pair positions of element e (n^2 entries, j-major: entry j n + i is
  /// the position of block entry (3i, 3j), -1 if node i or j is constrained).
  /// Entry (3i + a, 3j + b) sits at that position + b * column_length(node j) + a:
  /// a free node's three components are consecutive rows of every column, and
  /// its three columns have the same rows.
  const int* element_map(int e) const { return map_.data() + static_cast<size_t>(e) * block_size_; }
  /// Nonzeros in each column of a free node (3 x its free neighbours, itself
  /// included); 0 for a constrained node. Indexed by mesh node.
  int column_length(int node) const { return column_length_[node]; }
  int nodes_per_element() const { return nodes_; }
  /// The lowest-numbered element containing each node: assembly by column
  /// ownership (Assembler::hessian) gives part t of T the nodes whose first
  /// element lies in its element range [t ne / T, (t + 1) ne / T).
  int first_element(int node) const { return first_element_[node]; }
  /// Element ids grouped by colour.
  const std::vector<std::vector<int>>& colours() const { return colours_; }
  std::int64_t nonzeros() const { return static_cast<std::int64_t>(row_.size()); }
  /// Bytes held by the element-to-nonzero map (reported by benchmarks).
  size_t map_bytes() const { return map_.size() * sizeof(int); }

 private:
  // The structure alone, compressed columns with 32-bit rows (4 bytes per
  // nonzero; a matrix's 64-bit indices and values are another 16, held only by
  // the matrices themselves: 1.6 GB less at P3 n = 24).
  std::vector<std::int64_t> column_start_;
  std::vector<std::int32_t, UninitializedAllocator<std::int32_t>> row_;
  std::vector<int> map_;
  std::vector<int> column_length_;
  std::vector<int> first_element_;
  int nodes_ = 0;
  size_t block_size_ = 0;
  std::vector<std::vector<int>> colours_;
};

}  // namespace hofem
