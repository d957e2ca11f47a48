#include "element_checks.hpp"

#include "assembly/assembler.hpp"
#include "basis/reference_basis.hpp"
#include "material/material.hpp"
#include "mesh/mesh.hpp"

#include <fmt/format.h>

#include <random>

namespace hofem::verification {

namespace {

// One element whose reference nodes are the reference cell's nodes under a random
// affine map plus a random perturbation of every node (so order >= 2 elements are
// curved and Hex8 is non-affine), small enough to keep det J > 0.
Mesh single_element(CellType cell, int order, std::mt19937_64& rng) {
  const ReferenceBasis& b = lagrange_basis(cell, order);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::Matrix3d A = Eigen::Matrix3d::Identity();
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) A(i, j) += 0.2 * u(rng);
  const double size = cell == CellType::Tetrahedron ? 1.0 : 0.5;  // hex reference cell is [-1,1]^3
  Mesh m;
  m.cell = cell;
  m.order = order;
  m.nodes.resize(3, b.size());
  for (int i = 0; i < b.size(); ++i) {
    const Eigen::Vector3d xi = b.nodes().col(i);
    m.nodes.col(i) = size * A * xi + Eigen::Vector3d(0.3, -0.2, 0.1);
    for (int c = 0; c < 3; ++c) m.nodes(c, i) += 0.03 * u(rng);
  }
  m.elements.resize(b.size(), 1);
  for (int i = 0; i < b.size(); ++i) m.elements(i, 0) = i;
  return m;
}

}  // namespace

void add_element_checks(Report& report) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const LameParameters lame = LameParameters::from_young_poisson(1.0, 0.3);
  struct ElementCase {
    CellType cell;
    int order;
  };
  const ElementCase cases[] = {{CellType::Tetrahedron, 1}, {CellType::Tetrahedron, 2}, {CellType::Tetrahedron, 3},
                               {CellType::Hexahedron, 1}, {CellType::Hexahedron, 2}};
  for (const ElementCase& ec : cases) {
    const Mesh mesh = single_element(ec.cell, ec.order, rng);
    const DofMap dofs(mesh.num_nodes(), {});
    const Assembler assembler(mesh, dofs);
    const std::string element = lagrange_basis(ec.cell, ec.order).element_name();
    for (const std::string& name : material_names()) {
      const auto mat = make_material(name, lame);
      // Deformation: a random affine map near the identity plus nodal noise.
      Eigen::VectorXd x(3 * mesh.num_nodes());
      Eigen::Matrix3d G = Eigen::Matrix3d::Identity();
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) G(i, j) += 0.15 * u(rng);
      for (int n = 0; n < mesh.num_nodes(); ++n) {
        x.segment<3>(3 * n) = G * mesh.nodes.col(n);
        for (int c = 0; c < 3; ++c) x[3 * n + c] += 0.02 * u(rng);
      }
      Eigen::VectorXd g, gp, gm;
      SparseMatrix K = assembler.new_matrix();
      const double E = assembler.hessian(*mat, x, g, K, false);
      const Eigen::MatrixXd H(K);
      // Central differences, step h = 1e-6 (element size ~1): truncation
      // h^2/6 |E'''| ~ 1e-13 and rounding eps |E| / h ~ 1e-10 relative to the
      // gradient's scale; the bound 1e-7 leaves three orders for the distorted,
      // stiff cases (largest measured ~1e-9).
      const double h = 1e-6;
      Eigen::VectorXd g_fd(x.size());
      Eigen::MatrixXd H_fd(x.size(), x.size());
      for (int k = 0; k < x.size(); ++k) {
        Eigen::VectorXd xp = x, xm = x;
        xp[k] += h;
        xm[k] -= h;
        g_fd[k] = (assembler.energy(*mat, xp) - assembler.energy(*mat, xm)) / (2 * h);
        assembler.gradient(*mat, xp, gp);
        assembler.gradient(*mat, xm, gm);
        H_fd.col(k) = (gp - gm) / (2 * h);
      }
      const std::string label = fmt::format("{} {}", element, name);
      report.check("element.gradient_fd", label, (g - g_fd).cwiseAbs().maxCoeff() / g.cwiseAbs().maxCoeff(), 1e-7,
                   Compare::AtMost, "max |g - central difference of E| / max |g|, h = 1e-6");
      report.check("element.hessian_fd", label, (H - H_fd).cwiseAbs().maxCoeff() / H.cwiseAbs().maxCoeff(), 1e-7,
                   Compare::AtMost, "max |H - central difference of g| / max |H|, h = 1e-6");
      report.check("element.hessian_symmetry", label, (H - H.transpose()).cwiseAbs().maxCoeff() / H.cwiseAbs().maxCoeff(),
                   1e-14, Compare::AtMost, "max |H - H^T| / max |H| (assembled symmetric by construction: rounding)");
      report.measure("element.energy", label, E);
    }
    // Consistent mass: sum of all entries of one component block = rho |element|.
    const SparseMatrix M = assembler.mass_matrix(2.0, 2 * ec.order);
    double total = 0.0;
    for (Eigen::Index c = 0; c < M.outerSize(); ++c)
      for (SparseMatrix::InnerIterator it(M, c); it; ++it) total += it.value();
    // |element| = sum_i int N_i (partition of unity): the x-load of a unit body force.
    const Eigen::VectorXd unit_load =
        assembler.body_force_vector([](const Eigen::Vector3d&) { return Eigen::Vector3d(1.0, 0.0, 0.0); }, 2 * ec.order);
    const double vol = unit_load.sum();
    report.check("element.mass_total", element, std::fabs(total / 3.0 - 2.0 * vol) / (2.0 * vol), 1e-13, Compare::AtMost,
                 "sum of consistent mass entries / 3 = rho |element| (partition of unity), to rounding");
  }
}

}  // namespace hofem::verification
