#pragma once
// The spaces of a p-multigrid (thesis §3.1.3, Algorithm 3; deal.II step-75's
// p-coarsening): on one mesh, the Lagrange spaces of orders p = q_0 > q_1 > ... >
// q_L = 1, and the prolongation from each into the next finer one. Every coarser
// space lies inside the finer one (same elements, lower polynomial order), so a
// prolongation is the exact inclusion: a fine node's row holds the coarse basis
// evaluated at that node's reference position.
//
// Everything is per node and over free nodes: the three displacement components
// share the weights (P ⊗ I3, applied component-wise), and DofMap constrains whole
// nodes. The intermediate spaces are numbered like an order-q copy of the mesh's
// vertex mesh (upgrade_order), element e of every level being element e of the
// mesh.
//
// Constraints on a coarse level: a coarse node lies on a reference-cell entity
// (vertex, edge, face or interior, the facets through it); it is constrained when
// every fine node on the closure of that entity in its element is, so a Dirichlet
// face constrains the coarse nodes on it and nothing else. For order 1 this is
// "the vertex is constrained", as before.
#include "assembly/dof_map.hpp"
#include "mesh/mesh.hpp"

#include <Eigen/SparseCore>

#include <cstdint>
#include <vector>

namespace hofem {

/// Row-major sparse matrix (rows in parallel: y = P x, and P^T stored as its own rows).
using RowSparseMatrix = Eigen::SparseMatrix<double, Eigen::RowMajor, std::int64_t>;

struct PLevel {
  int order = 1;
  /// Free node index of each node of this level's space (-1: constrained).
  std::vector<int> free_node;
  int num_free_nodes = 0;
};

/// Prolongation from a coarser level's free nodes into a finer level's free nodes.
struct NodeTransfer {
  RowSparseMatrix P;  ///< fine free nodes x coarse free nodes
  RowSparseMatrix R;  ///< P^T, its rows (restriction by rows in parallel)
};

class PHierarchy {
 public:
  /// Levels of the given orders on the mesh of `dofs`: orders[0] must be the
  /// mesh's order, then strictly decreasing to 1. Throws std::invalid_argument
  /// for other orders, a DofMap of another mesh, or a Hex20 mesh with a level
  /// other than Hex8 (serendipity Hex20 has no intermediate order).
  PHierarchy(const Mesh& mesh, const DofMap& dofs, const std::vector<int>& orders);

  int num_levels() const { return static_cast<int>(levels_.size()); }
  const PLevel& level(int l) const { return levels_[l]; }
  /// From level l + 1 (coarser) into level l.
  const NodeTransfer& transfer(int l) const { return transfers_[l]; }

 private:
  std::vector<PLevel> levels_;
  std::vector<NodeTransfer> transfers_;
};

/// y = (P ⊗ I3) x and y = (R ⊗ I3) x on 3-component nodal vectors, rows in
/// parallel for large matrices; y is resized.
void apply_nodal(const RowSparseMatrix& M, const Eigen::VectorXd& x, Eigen::VectorXd& y);

}  // namespace hofem
