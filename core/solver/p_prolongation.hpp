#pragma once
// The coarse level of the p-multigrid (solver/p_multigrid.hpp): the order-1
// space (Tet4 / Hex8) on the vertices of the same mesh, its prolongation into
// the mesh's own order-p space, and the Galerkin coarse operator P^T A P.
// In thesis Algorithm 3 these are I_{l-1} (prolongation; its transpose is the
// restriction, line 5) and A_{l-1}; here there are two levels, l = 2 (order p)
// and l = 1 (order 1), as in the p-multigrid of deal.II (MGTransferGlobalCoarsening
// with p-coarsening) and MFEM (a low-order-refined / order-1 coarse space).
//
// Everything is over FREE DOFs: a coarse DOF is a vertex node's component that is
// free on the fine level (the vertex is the same node in both spaces, so the two
// levels agree on which vertex DOFs are constrained).
#include "assembly/dof_map.hpp"
#include "assembly/sparse_matrix.hpp"
#include "mesh/mesh.hpp"

#include <cstdint>
#include <vector>

namespace hofem {

/// Row-major copy of a sparse matrix (parallel row loops, e.g. y = P x).
using RowSparseMatrix = Eigen::SparseMatrix<double, Eigen::RowMajor, std::int64_t>;

struct PProlongation {
  /// fine free DOFs x coarse free DOFs. Row of a fine node's component c: the
  /// order-1 basis of any element containing the node, evaluated at its reference
  /// position (the same whichever element it is read from: the order-1 space is
  /// conforming), on that element's vertices' component-c DOFs. A vertex's row is
  /// the unit row of its own coarse DOF, so P has full column rank.
  SparseMatrix P;
  RowSparseMatrix P_rows;        ///< P again, row-major (prolongation by rows in parallel)
  std::vector<int> coarse_dofs;  ///< global DOF (3 * vertex + component) of each coarse free index
};

/// Prolongation of the order-1 space on mesh's vertices into the mesh's space.
/// Throws std::invalid_argument if dofs does not belong to mesh. For an order-1
/// mesh P is the identity (the caller decides whether that is useful).
PProlongation build_p_prolongation(const Mesh& mesh, const DofMap& dofs);

/// A_c = P^T A P for a symmetric A stored in full (A_c also stored in full).
/// analyze() computes A_c's pattern from A's pattern and P (once per pattern);
/// compute() only writes values into that pattern, in parallel over the coarse
/// columns (OpenMP), each thread scattering into its own dense accumulator.
class GalerkinProduct {
 public:
  void analyze(const SparseMatrix& A, const PProlongation& p);
  /// A_c's pattern with zero values (copy it into the matrix compute() fills).
  const SparseMatrix& zero_matrix() const { return pattern_; }
  /// Values of P^T A P into Ac, which must have zero_matrix()'s pattern; A must
  /// have the pattern given to analyze().
  void compute(const SparseMatrix& A, const PProlongation& p, SparseMatrix& Ac) const;
  bool analyzed() const { return analyzed_; }

 private:
  SparseMatrix pattern_;  ///< A_c's pattern, values zero
  bool analyzed_ = false;
};

}  // namespace hofem
