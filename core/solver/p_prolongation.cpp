#include "solver/p_prolongation.hpp"

#include "basis/reference_basis.hpp"

#include <Eigen/Core>
#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

namespace hofem {

namespace {

// Weights smaller than this are the order-1 basis' rounding at nodes where it is
// exactly zero; the true nonzero weights are at least 1/p (tets: barycentric
// coordinates k/p) or 1/2 (Hex20 edge midpoints), far above it.
constexpr double kZeroWeight = 1e-12;

// W(i, j) = order-1 basis function j (vertex j) at the order-p element's reference node i.
Eigen::MatrixXd vertex_weights(const Mesh& mesh) {
  const ReferenceBasis& fine = lagrange_basis(mesh.cell, mesh.order);
  const ReferenceBasis& linear = lagrange_basis(mesh.cell, 1);
  Eigen::MatrixXd W(fine.size(), linear.size());
  for (int i = 0; i < fine.size(); ++i) {
    W.row(i) = linear.evaluate(fine.nodes().col(i)).transpose();
    for (int j = 0; j < linear.size(); ++j)
      if (std::fabs(W(i, j)) < kZeroWeight) W(i, j) = 0.0;
  }
  return W;
}

}  // namespace

PProlongation build_p_prolongation(const Mesh& mesh, const DofMap& dofs) {
  if (dofs.num_dofs() != 3 * mesh.num_nodes())
    throw std::invalid_argument(fmt::format("p-prolongation: DOF map has {} DOFs, mesh has {} nodes (needs 3 per node)",
                                            dofs.num_dofs(), mesh.num_nodes()));
  const int nv = mesh.vertices_per_element(), npe = mesh.nodes_per_element();
  const Eigen::MatrixXd W = vertex_weights(mesh);
  if (W.rows() != npe)
    throw std::invalid_argument(
        fmt::format("p-prolongation: mesh has {} nodes per element, the order-{} basis {}", npe, mesh.order, W.rows()));

  // Coarse numbering: vertex nodes in increasing node id, components in order,
  // free ones only; monotone in the fine free numbering, so P is nearly banded
  // when the fine matrix is.
  std::vector<char> is_vertex(mesh.num_nodes(), 0);
  for (int e = 0; e < mesh.num_elements(); ++e)
    for (int j = 0; j < nv; ++j) is_vertex[mesh.elements(j, e)] = 1;
  PProlongation out;
  std::vector<int> coarse_index(dofs.num_dofs(), -1);
  for (int node = 0; node < mesh.num_nodes(); ++node) {
    if (!is_vertex[node]) continue;
    for (int c = 0; c < 3; ++c) {
      const int dof = 3 * node + c;
      if (dofs.free_index(dof) < 0) continue;
      coarse_index[dof] = static_cast<int>(out.coarse_dofs.size());
      out.coarse_dofs.push_back(dof);
    }
  }

  // One row per fine node, written from the first element that contains it.
  std::vector<Eigen::Triplet<double, std::int64_t>> entries;
  entries.reserve(static_cast<size_t>(dofs.num_free()) * 3);
  std::vector<char> done(mesh.num_nodes(), 0);
  for (int e = 0; e < mesh.num_elements(); ++e)
    for (int i = 0; i < npe; ++i) {
      const int node = mesh.elements(i, e);
      if (done[node]) continue;
      done[node] = 1;
      for (int c = 0; c < 3; ++c) {
        const int row = dofs.free_index(3 * node + c);
        if (row < 0) continue;
        for (int j = 0; j < nv; ++j) {
          // A constrained vertex DOF contributes nothing: coarse functions vanish
          // there, as fine ones do.
          const int col = coarse_index[3 * mesh.elements(j, e) + c];
          if (W(i, j) != 0.0 && col >= 0) entries.emplace_back(row, col, W(i, j));
        }
      }
    }
  out.P.resize(dofs.num_free(), static_cast<Eigen::Index>(out.coarse_dofs.size()));
  out.P.setFromTriplets(entries.begin(), entries.end());
  out.P.makeCompressed();
  out.P_rows = out.P;
  out.P_rows.makeCompressed();
  return out;
}

// Symbolic product, serial (once per pattern): column l of P^T A P reaches the
// coarse rows k of P's rows i over A's column j for every j in P's column l.
void GalerkinProduct::analyze(const SparseMatrix& A, const PProlongation& p) {
  const SparseMatrix& P = p.P;
  const RowSparseMatrix& R = p.P_rows;
  const Eigen::Index nc = P.cols();
  std::vector<std::int64_t> mark(nc, -1), rows;
  std::vector<Eigen::Triplet<double, std::int64_t>> entries;
  for (Eigen::Index l = 0; l < nc; ++l) {
    rows.clear();
    for (SparseMatrix::InnerIterator pj(P, l); pj; ++pj)
      for (SparseMatrix::InnerIterator a(A, pj.row()); a; ++a)
        for (RowSparseMatrix::InnerIterator pk(R, a.row()); pk; ++pk)
          if (mark[pk.col()] != l) {
            mark[pk.col()] = l;
            rows.push_back(pk.col());
          }
    for (std::int64_t k : rows) entries.emplace_back(k, l, 0.0);
  }
  pattern_.resize(nc, nc);
  pattern_.setFromTriplets(entries.begin(), entries.end());
  pattern_.makeCompressed();
  analyzed_ = true;
}

void GalerkinProduct::compute(const SparseMatrix& A, const PProlongation& p, SparseMatrix& Ac) const {
  if (!analyzed_) throw std::logic_error("GalerkinProduct::compute before analyze");
  if (Ac.rows() != pattern_.rows() || Ac.nonZeros() != pattern_.nonZeros() || !Ac.isCompressed())
    throw std::logic_error("GalerkinProduct::compute: Ac does not have the analysed pattern");
  const SparseMatrix& P = p.P;
  const RowSparseMatrix& R = p.P_rows;
  const Eigen::Index nc = P.cols();
  const std::int64_t* outer = Ac.outerIndexPtr();
  const std::int64_t* inner = Ac.innerIndexPtr();
  double* values = Ac.valuePtr();
#pragma omp parallel if (nc >= 2000)
  {
    Eigen::VectorXd acc = Eigen::VectorXd::Zero(nc);  // this thread's dense column
#pragma omp for schedule(dynamic, 64)
    for (Eigen::Index l = 0; l < nc; ++l) {
      for (SparseMatrix::InnerIterator pj(P, l); pj; ++pj)
        for (SparseMatrix::InnerIterator a(A, pj.row()); a; ++a) {
          const double w = a.value() * pj.value();
          for (RowSparseMatrix::InnerIterator pk(R, a.row()); pk; ++pk) acc[pk.col()] += pk.value() * w;
        }
      for (std::int64_t q = outer[l]; q < outer[l + 1]; ++q) {
        values[q] = acc[inner[q]];
        acc[inner[q]] = 0.0;
      }
    }
  }
}

}  // namespace hofem
