#include "solver/p_hierarchy.hpp"

#include "basis/reference_basis.hpp"
#include "mesh/mesh_upgrade.hpp"
#include "basis/element_orders.hpp"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

namespace hofem {

namespace {

// Basis weights below this are rounding at nodes where the coarse basis function
// is exactly zero; true weights are at least ~1/p^3 (tets) or 1/4 (Hex20 -> Hex8).
constexpr double kZeroWeight = 1e-12;

// The reference-cell facets through a point, as bits: tet facet v is lambda_v = 0
// (lambda_0 = 1 - xi - eta - zeta, lambda_k = xi_k), hex facets xi_k = -1 (bit 2k)
// and xi_k = +1 (bit 2k + 1). A node lies on the closure of another node's entity
// when its facets include all of the other's.
unsigned facets(CellType cell, const Eigen::Vector3d& xi) {
  constexpr double tol = 1e-12;
  unsigned mask = 0;
  if (cell == CellType::Tetrahedron) {
    if (std::abs(1.0 - xi.sum()) < tol) mask |= 1u;
    for (int k = 0; k < 3; ++k)
      if (std::abs(xi[k]) < tol) mask |= 1u << (k + 1);
  } else {
    for (int k = 0; k < 3; ++k) {
      if (std::abs(xi[k] + 1.0) < tol) mask |= 1u << (2 * k);
      if (std::abs(xi[k] - 1.0) < tol) mask |= 1u << (2 * k + 1);
    }
  }
  return mask;
}

// The order-1 mesh of a mesh's vertices (vertices renumbered in increasing node
// id), element e being element e of the mesh.
Mesh vertex_mesh(const Mesh& mesh) {
  const int nv = mesh.vertices_per_element();
  std::vector<int> id(mesh.num_nodes(), -2);  // -2: not a vertex, -1: a vertex not numbered yet
  int count = 0;
  for (int e = 0; e < mesh.num_elements(); ++e)
    for (int j = 0; j < nv; ++j) id[mesh.elements(j, e)] = -1;
  for (int n = 0; n < mesh.num_nodes(); ++n)
    if (id[n] == -1) id[n] = count++;
  Mesh v;
  v.cell = mesh.cell;
  v.order = 1;
  v.nodes.resize(3, count);
  for (int n = 0; n < mesh.num_nodes(); ++n)
    if (id[n] >= 0) v.nodes.col(id[n]) = mesh.nodes.col(n);
  v.elements.resize(nv, mesh.num_elements());
  for (int e = 0; e < mesh.num_elements(); ++e)
    for (int j = 0; j < nv; ++j) v.elements(j, e) = id[mesh.elements(j, e)];
  return v;
}

// Coarse level's free nodes from the finer level (element-wise connectivity of
// both, same elements): the entity rule of the header.
PLevel coarse_level(const Mesh& fine, const PLevel& fine_level, const Mesh& coarse) {
  const ReferenceBasis& fb = lagrange_basis(fine.cell, fine.order);
  const ReferenceBasis& cb = lagrange_basis(coarse.cell, coarse.order);
  std::vector<unsigned> fine_mask(fb.size()), coarse_mask(cb.size());
  for (int i = 0; i < fb.size(); ++i) fine_mask[i] = facets(fine.cell, fb.nodes().col(i));
  for (int j = 0; j < cb.size(); ++j) coarse_mask[j] = facets(coarse.cell, cb.nodes().col(j));
  PLevel out;
  out.order = coarse.order;
  out.free_node.assign(coarse.num_nodes(), -2);  // -2: not decided yet
  for (int e = 0; e < coarse.num_elements(); ++e)
    for (int j = 0; j < cb.size(); ++j) {
      int& state = out.free_node[coarse.elements(j, e)];
      if (state != -2) continue;
      bool all_constrained = true;
      for (int i = 0; i < fb.size() && all_constrained; ++i)
        if ((fine_mask[i] & coarse_mask[j]) == coarse_mask[j] && fine_level.free_node[fine.elements(i, e)] >= 0)
          all_constrained = false;
      state = all_constrained ? -1 : 0;
    }
  for (int& f : out.free_node) f = f == 0 ? out.num_free_nodes++ : -1;
  return out;
}

NodeTransfer make_transfer(const Mesh& fine, const PLevel& fine_level, const Mesh& coarse, const PLevel& coarse_level) {
  const ReferenceBasis& fb = lagrange_basis(fine.cell, fine.order);
  const ReferenceBasis& cb = lagrange_basis(coarse.cell, coarse.order);
  Eigen::MatrixXd W(fb.size(), cb.size());  // coarse basis j at fine reference node i
  for (int i = 0; i < fb.size(); ++i) {
    W.row(i) = cb.evaluate(fb.nodes().col(i)).transpose();
    for (int j = 0; j < cb.size(); ++j)
      if (std::abs(W(i, j)) < kZeroWeight) W(i, j) = 0.0;
  }
  std::vector<Eigen::Triplet<double, std::int64_t>> entries;
  std::vector<char> done(fine.num_nodes(), 0);
  for (int e = 0; e < fine.num_elements(); ++e)
    for (int i = 0; i < fb.size(); ++i) {
      const int node = fine.elements(i, e);
      const int row = fine_level.free_node[node];
      if (done[node] || row < 0) continue;
      done[node] = 1;
      for (int j = 0; j < cb.size(); ++j) {
        const int col = coarse_level.free_node[coarse.elements(j, e)];
        if (W(i, j) != 0.0 && col >= 0) entries.emplace_back(row, col, W(i, j));
      }
    }
  NodeTransfer t;
  t.P.resize(fine_level.num_free_nodes, coarse_level.num_free_nodes);
  t.P.setFromTriplets(entries.begin(), entries.end());
  t.P.makeCompressed();
  t.R = t.P.transpose();
  t.R.makeCompressed();
  return t;
}

}  // namespace

PHierarchy::PHierarchy(const Mesh& mesh, const DofMap& dofs, const std::vector<int>& orders) {
  if (dofs.num_dofs() != 3 * mesh.num_nodes())
    throw std::invalid_argument(fmt::format("p-hierarchy: DOF map has {} DOFs, mesh has {} nodes (needs 3 per node)",
                                            dofs.num_dofs(), mesh.num_nodes()));
  if (orders.empty() || orders.front() != mesh.order || orders.back() != 1)
    throw std::invalid_argument(fmt::format("p-hierarchy: orders must run from the mesh's order {} down to 1", mesh.order));
  for (size_t k = 1; k < orders.size(); ++k)
    if (orders[k] >= orders[k - 1]) throw std::invalid_argument("p-hierarchy: orders must decrease strictly");
  for (int order : orders) check_element_order(mesh.cell, order, "p-hierarchy level");

  PLevel fine;
  fine.order = mesh.order;
  fine.free_node.assign(mesh.num_nodes(), -1);
  for (int n = 0; n < mesh.num_nodes(); ++n) {
    const int f = dofs.free_index(3 * n);
    if (f >= 0) {
      fine.free_node[n] = f / 3;  // free DOFs in global order: a free node's three are 3k, 3k+1, 3k+2
      ++fine.num_free_nodes;
    }
  }
  levels_.push_back(std::move(fine));
  if (orders.size() == 1) return;

  const Mesh vertices = vertex_mesh(mesh);
  Mesh finer = mesh;  // level l's connectivity (the mesh itself for l = 0)
  for (size_t k = 1; k < orders.size(); ++k) {
    Mesh coarser = orders[k] == 1 ? vertices : upgrade_order(vertices, orders[k]);
    PLevel level = coarse_level(finer, levels_.back(), coarser);
    transfers_.push_back(make_transfer(finer, levels_.back(), coarser, level));
    levels_.push_back(std::move(level));
    finer = std::move(coarser);
  }
}

void apply_nodal(const RowSparseMatrix& M, const Eigen::VectorXd& x, Eigen::VectorXd& y) {
  const Eigen::Index n = M.rows();
  if (y.size() != 3 * n) y.resize(3 * n);
  const std::int64_t* outer = M.outerIndexPtr();
  const std::int64_t* inner = M.innerIndexPtr();
  const double* val = M.valuePtr();
#pragma omp parallel for schedule(static) if (M.nonZeros() >= 50000)
  for (Eigen::Index i = 0; i < n; ++i) {
    double a0 = 0.0, a1 = 0.0, a2 = 0.0;
    for (std::int64_t q = outer[i]; q < outer[i + 1]; ++q) {
      const double w = val[q];
      const double* xc = x.data() + 3 * inner[q];
      a0 += w * xc[0];
      a1 += w * xc[1];
      a2 += w * xc[2];
    }
    y[3 * i] = a0, y[3 * i + 1] = a1, y[3 * i + 2] = a2;
  }
}

}  // namespace hofem
