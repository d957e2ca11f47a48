#include "fcm_setup_checks.hpp"

#include "assembly/assembler.hpp"
#include "embedded/embedded_quadrature.hpp"
#include "embedded/finite_cell_quadrature.hpp"
#include "material/material.hpp"
#include "mesh/box_mesh.hpp"
#include "mesh/tube_mesh.hpp"

#include <chrono>

namespace hofem::verification {

namespace {

struct Setup {
  CellQuadrature cells;
  double seconds = 0.0;
};

// As SceneEmbedding builds them (simplified, stabilised, folded), on the fast
// paths or on the reference ones.
Setup build(const Mesh& background, const std::vector<Tetrahedron>& tets, bool fast) {
  const auto t0 = std::chrono::steady_clock::now();
  FiniteCellOptions fo;
  fo.fit_mass = fast;
  fo.simplification.fast = fast;
  Setup s;
  s.cells = finite_cell_quadrature(background, tets, fo);
  FiniteCellStabilisation so;
  so.simplify_degree = s.cells.stiffness_degree;
  so.simplification.fast = fast;
  stabilise_finite_cells(background, s.cells, so);
  s.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return s;
}

double max_abs(const SparseMatrix& A) { return A.nonZeros() > 0 ? A.coeffs().cwiseAbs().maxCoeff() : 0.0; }

}  // namespace

void add_fcm_setup_checks(Report& report) {
  const std::string g = "embedded.setup";
  const Mesh background = box_mesh(BoxSpec{{-1, -1, 0}, {1, 1, 3}, {2, 2, 3}}, CellType::Hexahedron, 2);
  const std::vector<Tetrahedron> tets =
      mesh_tetrahedra(hollow_cylinder_mesh(0.5, 1.0, 3.0, 1, 16, 8, CellType::Tetrahedron, 1));
  const Setup reference = build(background, tets, false), fast = build(background, tets, true);

  int cut = 0, different = 0;
  double worst_weight = 0.0;
  for (int e = 0; e < background.num_elements(); ++e) {
    const auto& a = reference.cells.rules[e];
    const auto& b = fast.cells.rules[e];
    if (!a || !b || a->rule.size() == 0) continue;  // uncut or empty: the standard rule on both
    ++cut;
    if (a->rule.points != b->rule.points) {
      ++different;
      continue;
    }
    worst_weight = std::max(worst_weight, (a->rule.weights - b->rule.weights).cwiseAbs().maxCoeff() /
                                              a->rule.weights.cwiseAbs().maxCoeff());
  }
  report.check(g, "cut cells", cut, 12, Compare::AtLeast,
               "every cell of the 2 x 2 x 3 grid is cut by the tube's walls (the comparison below covers them all)");
  report.check(g, "cut cells whose stiffness points differ from the reference", different, 0, Compare::AtMost,
               "CholeskyQR2 and the updated QR give the active set the same iterates as the SVD and the pivoted QR "
               "in exact arithmetic (orthogonal invariance, quadrature_simplification.cpp), so the same points are "
               "kept, bit for bit, in the same order; a different support would be a different rule");
  report.measure(g, "max relative weight difference", worst_weight,
                 "max |w_fast - w_ref| / max |w_ref| per cell: the last least-squares solve's conditioning "
                 "(kappa up to ~1e5 times eps); the matrices below are what the weights are for");

  const DofMap dofs(background.num_nodes(), {});
  const auto material = make_material("linear", LameParameters::from_young_poisson(1.0, 0.3));
  const Eigen::VectorXd x = Eigen::Map<const Eigen::VectorXd>(background.nodes.data(), 3 * background.num_nodes());
  auto matrices = [&](const Setup& s) {
    Assembler a(background, dofs);
    a.set_element_rules(s.cells.element_rules());
    SparseMatrix K = a.new_matrix();
    Eigen::VectorXd gradient;
    a.hessian(*material, x, gradient, K, false);
    return std::pair{K, a.mass_matrix(1.0, 2 * background.order)};
  };
  const auto [K0, M0] = matrices(reference);
  const auto [K1, M1] = matrices(fast);
  report.check(g, "stiffness: max |K_fast - K_ref| / max |K_ref|", max_abs(K1 - K0) / max_abs(K0), 1e-13,
               Compare::AtMost,
               "the same points with weights whose degree-6 moments agree to the LPs' residual (<= 1e-15 of the "
               "weights' sum, both paths), and the linear-elastic Hex20 integrand has degree 6: agreement to "
               "rounding; 1e-13 is 100x the sums' rounding of ~1e-15");
  report.check(g, "mass: max |M_fitted - M_clipped| / max |M_clipped|", max_abs(M1 - M0) / max_abs(M0), 1e-13,
               Compare::AtMost,
               "the fitted rule keeps every moment of degree <= 8 of the clipped one to rounding "
               "(FittedRule::moment_residual) and N_i N_j has degree 8 on an affine Hex20 cell; sum |w| / sum w "
               "of the fitted rules (below) bounds the amplification; 1e-13 is 100x rounding");
  report.check(g, "fitted mass rules: max moment residual", fast.cells.max_mass_moment_residual, 1e-13,
               Compare::AtMost, "relative to the clipped weights' sum; rounding of ~1e4-term sums is ~1e-15");
  report.measure(g, "fitted mass rules: max sum |w| / sum w", fast.cells.max_mass_weight_ratio,
                 "1 for positive weights; the factor by which rounding of the fitted weights is amplified");
  report.measure(g, "mass points, clipped", static_cast<double>(reference.cells.mass_points), "over cut cells");
  report.measure(g, "mass points, fitted", static_cast<double>(fast.cells.mass_points), "C(8+3, 3) = 165 per cut cell");
  report.measure(g, "set-up seconds, reference", reference.seconds, "rules, stabilisation and fold; 2 threads");
  report.measure(g, "set-up seconds, fast", fast.seconds, "the same, as scenes build them");
}

}  // namespace hofem::verification
