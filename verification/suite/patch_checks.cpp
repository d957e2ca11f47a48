#include "element_checks.hpp"
#include "study/manufactured_solution.hpp"

#include "material/material.hpp"
#include "mesh/box_mesh.hpp"
#include "mesh/mesh_upgrade.hpp"
#include "problem/static_elasticity.hpp"

#include <fmt/format.h>

#include <random>

namespace hofem::verification {

namespace {

// A polynomial displacement of total degree p with random coefficients, with
// its gradient and second derivatives (for the body force).
struct PolynomialField {
  int degree;
  std::vector<std::array<int, 3>> exps;
  Eigen::MatrixXd coef;  // 3 x terms

  PolynomialField(int p, std::mt19937_64& rng) : degree(p) {
    for (int a = 0; a <= p; ++a)
      for (int b = 0; a + b <= p; ++b)
        for (int c = 0; a + b + c <= p; ++c) exps.push_back({a, b, c});
    std::uniform_real_distribution<double> u(-0.1, 0.1);
    coef.resize(3, static_cast<Eigen::Index>(exps.size()));
    for (Eigen::Index i = 0; i < coef.size(); ++i) coef.data()[i] = u(rng);
  }
  static double mono(const Eigen::Vector3d& X, std::array<int, 3> e) {
    double v = 1.0;
    for (int c = 0; c < 3; ++c) {
      if (e[c] < 0) return 0.0;
      v *= std::pow(X[c], e[c]);
    }
    return v;
  }
  // d^k/dX... of a monomial: multiply by exponents and lower them.
  static double deriv(const Eigen::Vector3d& X, std::array<int, 3> e, int c1, int c2 = -1) {
    double f = e[c1];
    e[c1] -= 1;
    if (c2 >= 0) {
      f *= e[c2];
      e[c2] -= 1;
    }
    return f == 0.0 ? 0.0 : f * mono(X, e);
  }
  Eigen::Vector3d value(const Eigen::Vector3d& X) const {
    Eigen::Vector3d v = Eigen::Vector3d::Zero();
    for (size_t t = 0; t < exps.size(); ++t) v += coef.col(t) * mono(X, exps[t]);
    return v;
  }
  // d^2 u_k / dX_l dX_j
  double second(const Eigen::Vector3d& X, int k, int l, int j) const {
    double s = 0.0;
    for (size_t t = 0; t < exps.size(); ++t) s += coef(k, t) * deriv(X, exps[t], l, j);
    return s;
  }
};

struct PatchCase {
  CellType cell;
  int order;
  int degree;        // polynomial degree reproduced
  bool perturbed;    // random interior vertices (non-affine for hexes)
  bool sheared;      // global affine map (keeps hexes affine)
};

}  // namespace

void add_patch_checks(Report& report) {
  const auto mat = make_material("linear", LameParameters::from_young_poisson(1.0, 0.3));
  const Mat9 A = mat->stress_derivative(Mat3::Identity());  // constant for linear elasticity
  const PatchCase cases[] = {
      {CellType::Tetrahedron, 1, 1, true, true}, {CellType::Tetrahedron, 2, 2, true, true},
      {CellType::Tetrahedron, 3, 3, true, true}, {CellType::Tetrahedron, 4, 4, true, true},
      {CellType::Hexahedron, 1, 1, true, false}, {CellType::Hexahedron, 2, 1, true, false},
      {CellType::Hexahedron, 2, 2, false, true},
  };
  std::mt19937_64 rng(11);
  for (const PatchCase& pc : cases) {
    Mesh mesh = pc.cell == CellType::Tetrahedron ? box_tet_mesh(unit_cube(3)) : box_hex_mesh(unit_cube(3));
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    if (pc.perturbed) {
      std::vector<char> bnd(mesh.num_nodes(), 0);
      for (int n : mesh.node_set("boundary")) bnd[n] = 1;
      for (int n = 0; n < mesh.num_nodes(); ++n)
        if (!bnd[n])
          for (int c = 0; c < 3; ++c) mesh.nodes(c, n) += 0.08 * u(rng);  // h = 1/3
    }
    if (pc.sheared) {
      Eigen::Matrix3d S;
      S << 1.0, 0.3, -0.1, 0.0, 0.9, 0.25, 0.1, 0.0, 1.1;
      mesh.nodes = S * mesh.nodes;
    }
    if (pc.order > 1) mesh = upgrade_order(mesh, pc.order);
    const PolynomialField field(pc.degree, rng);
    VectorField body_force = [&](const Eigen::Vector3d& X) {
      Eigen::Matrix3d H[3];
      for (int k = 0; k < 3; ++k)
        for (int l = 0; l < 3; ++l)
          for (int j = 0; j < 3; ++j) H[k](l, j) = field.second(X, k, l, j);
      return equilibrium_body_force(A, H);
    };
    StaticOptions opt;
    // Exact integration on affine elements: stiffness 2(p-1), load (p-2) + p.
    opt.quadrature_degree = pc.cell == CellType::Tetrahedron ? std::max(1, 2 * (pc.order - 1)) : 2 * pc.order;
    opt.load_degree = 2 * pc.order;
    opt.newton.rtol = 1e-13;
    StaticElasticity problem(mesh, *mat, {{mesh.node_set("boundary"), [&](const Eigen::Vector3d& X) { return field.value(X); }}},
                             body_force, opt);
    const StaticReport rep = problem.solve();
    double err = 0.0, scale = 0.0;
    for (int n = 0; n < mesh.num_nodes(); ++n) {
      const Eigen::Vector3d exact = field.value(mesh.nodes.col(n));
      err = std::max(err, (problem.displacement().segment<3>(3 * n) - exact).cwiseAbs().maxCoeff());
      scale = std::max(scale, exact.cwiseAbs().maxCoeff());
    }
    const std::string label = fmt::format("{}{} degree-{} field on a {}{} mesh{}", name(pc.cell), pc.order, pc.degree,
                                          pc.perturbed ? "perturbed" : "", pc.sheared ? (pc.perturbed ? ", sheared" : "sheared") : "",
                                          rep.converged ? "" : " (NOT CONVERGED)");
    // Round-off of a direct solve of a 3x3x3-cell patch: cond(K) <~ 1e3-1e4, so
    // nodal values are exact to ~cond * eps ~ 1e-13 relative (measured <= 2e-15).
    report.check("patch.polynomial_reproduction", label, rep.converged ? err / scale : 1.0, 1e-12, Compare::AtMost,
                 "max nodal |u_h - u_exact| / max |u_exact| with matching body force");
  }
}

}  // namespace hofem::verification
