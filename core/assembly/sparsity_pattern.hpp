#pragma once
// The sparsity pattern of an element-assembled matrix over the free DOFs,
// computed once per (mesh, DofMap), with
//  - an element-to-nonzero map: for each element the position in the matrix's
//    value array of every entry of its (3n x 3n) block (-1 where a row or column
//    is constrained), so re-assembly only writes values;
//  - an element colouring: elements of one colour share no node, so one colour
//    is assembled in parallel without atomics, in a fixed order (results are
//    bitwise reproducible whatever the thread count).
#include "assembly/dof_map.hpp"
#include "assembly/sparse_matrix.hpp"
#include "mesh/mesh.hpp"

#include <vector>

namespace hofem {

class SparsityPattern {
 public:
  SparsityPattern(const Mesh& mesh, const DofMap& dofs);

  /// A matrix with this pattern and all values zero (compressed).
  const SparseMatrix& zero_matrix() const { return pattern_; }
  /// Gives K this pattern with all values zero, like K = zero_matrix() but
  /// filling the index and value arrays on every thread: the first touch of a
  /// ~100 MB array is page faults, which a serial copy takes one at a time.
  void shape(SparseMatrix& K) const;
  /// Sets every value of a matrix of this pattern to zero (in parallel).
  void zero_values(SparseMatrix& K) const;
  /// Positions of element e's block entries in the value array, row-major over
  /// (3 i + a, 3 j + b) of the element block: size (3n)^2.
  const int* element_map(int e) const { return map_.data() + static_cast<size_t>(e) * block_size_; }
  int block_dim() const { return block_dim_; }
  /// Element ids grouped by colour.
  const std::vector<std::vector<int>>& colours() const { return colours_; }
  std::int64_t nonzeros() const { return pattern_.nonZeros(); }
  /// Bytes held by the element-to-nonzero map (reported by benchmarks).
  size_t map_bytes() const { return map_.size() * sizeof(int); }

 private:
  SparseMatrix pattern_;
  std::vector<int> map_;
  int block_dim_ = 0;
  size_t block_size_ = 0;
  std::vector<std::vector<int>> colours_;
};

}  // namespace hofem
