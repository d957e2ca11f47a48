#include "solver_checks.hpp"

#include <fmt/format.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "assembly/assembler.hpp"
#include "material/material.hpp"
#include "mesh/box_mesh.hpp"
#include "elastic_test_systems.hpp"
#include "linalg/krylov.hpp"
#include "linalg/linear_solver.hpp"
#include "solver/solver_factory.hpp"

namespace hofem::verification {

namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();

// A clamped linear-elastic cube with a label and the smooth right-hand side.
struct ElasticSystem {
  std::string label;
  ClampedElasticBody body;
  Eigen::VectorXd b;
  ElasticSystem(std::string l, CellType cell, int order, int n)
      : label(std::move(l)), body(cell, order, n), b(smooth_rhs(body.unknowns())) {}
};

// Smallest eigenvalue of an SPD matrix by inverse iteration with CHOLMOD. The
// Rayleigh quotient approaches lambda_min from above, so 1/lambda bounds
// ||A^-1|| from below and the error bound built from it can only be stricter.
double smallest_eigenvalue(const SparseMatrix& A, LinearSolver& chol) {
  Eigen::VectorXd v = smooth_rhs(A.rows()).normalized(), w;
  double lambda = 0.0;
  for (int k = 0; k < 60; ++k) {
    chol.solve(v, w);
    lambda = 1.0 / v.dot(w);
    v = w.normalized();
  }
  return lambda;
}

// Largest absolute row sum: an upper bound on lambda_max (Gershgorin).
double gershgorin_lambda_max(const SparseMatrix& A) {
  Eigen::VectorXd row_sum = Eigen::VectorXd::Zero(A.rows());
  for (Eigen::Index j = 0; j < A.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(A, j); it; ++it) row_sum[it.row()] += std::abs(it.value());
  return row_sum.maxCoeff();
}

// Every solver reaches rtol and agrees with CHOLMOD within the forward-error
// bound that rtol implies: ||x - x*|| <= ||A^-1|| ||r|| <= rtol ||b|| /
// lambda_min.
void add_spd_rows(Report& report) {
  const double rtol = 1e-10;
  const ElasticSystem systems[] = {
      {"Tet4 n=6", CellType::Tetrahedron, 1, 6}, {"Tet10 n=3", CellType::Tetrahedron, 2, 3},
      {"Tet20 n=2", CellType::Tetrahedron, 3, 2}, {"Hex8 n=6", CellType::Hexahedron, 1, 6},
      {"Hex20 n=3", CellType::Hexahedron, 2, 3}};
  for (const ElasticSystem& s : systems) {
    auto chol = make_linear_solver("cholmod");
    chol->analyze(s.body.K);
    if (!chol->factorize(s.body.K)) throw std::runtime_error("solver checks: stiffness not SPD for " + s.label);
    Eigen::VectorXd x_ref, x;
    chol->solve(s.b, x_ref);
    const double lambda_min = smallest_eigenvalue(s.body.K, *chol);
    // CHOLMOD's own error (backward stable: ~cond * eps) is far below this
    // bound.
    const double bound = rtol * s.b.norm() / (lambda_min * x_ref.norm());
    // Two backward-stable direct solvers differ by at most the sum of their
    // forward errors, each <= cond(K) * (a small multiple of eps) (Higham,
    // Accuracy and Stability, Thm. 10.4 for Cholesky; LU with the pivoting
    // UMFPACK uses on an SPD matrix behaves alike). cond(K) is bounded from
    // above by the Gershgorin bound on lambda_max over the inverse-iteration
    // lambda_min; 100 covers the two solvers' constants.
    const double cond_bound = gershgorin_lambda_max(s.body.K) / lambda_min;
    const double direct_bound = 100.0 * cond_bound * kEps;
    report.measure("solvers.spd", s.label + " unknowns", static_cast<double>(s.body.K.rows()));
    for (const std::string& name : linear_solver_names()) {
      if (name == "cholmod") continue;
      if (name.ends_with("+pmg") && s.body.mesh.order < 2) continue;  // no coarser p level
      std::unique_ptr<LinearSolver> solver;
      std::string error;
      double residual = std::numeric_limits<double>::quiet_NaN(), diff = residual;
      bool iterative = true;

      try {
        solver = make_linear_solver(name);
        solver->set_mesh_view(s.body.mesh_view());
        solver->set_relative_tolerance(rtol);
        iterative = solver->is_iterative();
        solver->analyze(s.body.K);
        if (!solver->factorize(s.body.K)) throw std::runtime_error("set-up refused the SPD matrix");
        solver->solve(s.b, x);
        residual = (s.b - s.body.K * x).norm() / s.b.norm();
        diff = (x - x_ref).norm() / x_ref.norm();
      } catch (const std::exception& e) {
        error = e.what();
      }
      const std::string why =
          error.empty() ? fmt::format("{} iterations", solver ? solver->last_iterations() : 0) : "failed: " + error;
      if (iterative)
        report.check("solvers.spd", fmt::format("{} {} relative residual", s.label, name), residual, rtol,
                     Compare::AtMost, "requested tolerance (true residual ||b - Ax|| / ||b||); " + why);
      report.check("solvers.spd", fmt::format("{} {} vs cholmod", s.label, name), diff,
                   iterative ? bound : direct_bound, Compare::AtMost,
                   iterative ? fmt::format("rtol ||b|| / (lambda_min ||x||), lambda_min = {:.3e}; {}", lambda_min, why)
                             : fmt::format("direct vs direct: 100 cond(K) eps, cond(K) <= {:.3e} (Gershgorin "
                                           "lambda_max / lambda_min); {}",
                                           cond_bound, why));
    }
  }
}

// Dense M^-1 from unit vectors: symmetric to rounding and positive definite
// (what CG, CR and MINRES require of a preconditioner).
void add_preconditioner_rows(Report& report) {
  const ElasticSystem systems[] = {{"Tet10 n=2", CellType::Tetrahedron, 2, 2},
                                   {"Hex8 n=4", CellType::Hexahedron, 1, 4}};
  for (const ElasticSystem& s : systems)
    for (const std::string& name : preconditioner_names()) {
      if (name == "pmg" && s.body.mesh.order < 2) continue;
      std::unique_ptr<Preconditioner> M;
      std::string error;
      try {
        M = make_preconditioner(name);
        M->set_mesh_view(s.body.mesh_view());
        if (!M->setup(s.body.K)) error = M->last_error();
      } catch (const std::exception& e) {
        error = e.what();
      }
      if (!error.empty()) {  // the row it would have measured, unmeasured (NaN fails)
        report.check("solvers.preconditioner_spd", fmt::format("{} {} lambda_min / lambda_max", s.label, name),
                     std::numeric_limits<double>::quiet_NaN(), 1e3 * kEps, Compare::AtLeast,
                     "set-up failed on an SPD matrix: " + error);
        continue;
      }
      const Eigen::MatrixXd Minv = dense_inverse(*M, s.body.unknowns());
      const double scale = Minv.cwiseAbs().maxCoeff();
      report.check("solvers.preconditioner_spd", fmt::format("{} {} asymmetry", s.label, name),
                   (Minv - Minv.transpose()).cwiseAbs().maxCoeff() / scale, 1e-12, Compare::AtMost,
                   "max |M^-1 - M^-T| / max |M^-1|: symmetric up to rounding "
                   "of its sweeps (~n eps)");
      const Eigen::VectorXd ev =
          Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(0.5 * (Minv + Minv.transpose()), Eigen::EigenvaluesOnly)
              .eigenvalues();
      report.check("solvers.preconditioner_spd", fmt::format("{} {} lambda_min / lambda_max", s.label, name),
                   ev.minCoeff() / ev.maxCoeff(), 1e3 * kEps, Compare::AtLeast,
                   "positive definite: above the dense eigensolver's "
                   "resolution (~n eps lambda_max)");
    }
}

// A preconditioner's set-up on the indefinite matrix, as a row. Jacobi divides by
// the diagonal and must refuse exactly when K has a non-positive diagonal entry:
// the row holds that entry against 0 from the side its verdict implies. The
// others have no reason to refuse (none is the identity; the Schwarz blocks are
// reflected, eq. 14, and SPD by design): a refusal is a failing row with its reason.
void check_set_up(Report& report, const std::string& pc, const SparseMatrix& K, const std::string& error) {
  const std::string name = fmt::format("{} set-up on the indefinite matrix", pc);
  if (pc == "jacobi") {
    const double d = K.diagonal().minCoeff();
    if (error.empty())
      report.check("solvers.indefinite", name + ": smallest diagonal entry of K", d,
                   std::numeric_limits<double>::denorm_min(), Compare::AtLeast,
                   "accepted: Jacobi needs every diagonal entry > 0 (>= the least positive double), which K has (only "
                   "its eigenvalues go negative)");
    else
      report.check("solvers.indefinite", name + ": smallest diagonal entry of K", d, 0.0, Compare::AtMost,
                   "refused, which a non-positive diagonal entry explains: " + error);
    return;
  }
  if (!error.empty())
    report.check("solvers.indefinite", name, std::numeric_limits<double>::quiet_NaN(), 0.0, Compare::AtMost,
                 "refused, with no reason to (it needs no positive diagonal): " + error);
}

// Neo-Hookean cube pressed to 35 % of its height with a lateral shear wave,
// Hessian without PSD projection: indefinite (thesis §5.3.2's setting).
void add_indefinite_rows(Report& report) {
  Mesh mesh = box_mesh(unit_cube(3), CellType::Tetrahedron, 2);
  const DofMap dofs(mesh.num_nodes(), mesh.node_set("zmin"));
  const Assembler a(mesh, dofs);
  const auto mat = make_material("neohookean", LameParameters::from_young_poisson(1.0, 0.3));
  Eigen::VectorXd x(3 * mesh.num_nodes()), g;
  for (int i = 0; i < mesh.num_nodes(); ++i) {
    const Eigen::Vector3d X = mesh.nodes.col(i);
    x.segment<3>(3 * i) = Eigen::Vector3d(X.x() + 0.1 * X.z() * std::sin(3.0 * X.y()), X.y(), 0.35 * X.z());
  }
  SparseMatrix K = a.new_matrix();
  a.hessian(*mat, x, g, K, false);
  const Eigen::VectorXd ev =
      Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(Eigen::MatrixXd(K), Eigen::EigenvaluesOnly).eigenvalues();
  int negative = 0;
  for (Eigen::Index i = 0; i < ev.size(); ++i) negative += ev[i] < 0.0;
  report.check("solvers.indefinite", "NH compressed cube Hessian negative eigenvalues", negative, 1, Compare::AtLeast,
               fmt::format("the test matrix must be indefinite: lambda_min = "
                           "{:.3e}, lambda_max = {:.3e}, {} unknowns",
                           ev.minCoeff(), ev.maxCoeff(), K.rows()));
  const Eigen::VectorXd b = smooth_rhs(K.rows());
  KrylovOptions opt;
  opt.rtol = 1e-8;
  opt.max_iterations = 20000;
  opt.restart = static_cast<int>(K.rows());  // full GMRES: restarted GMRES can
                                             // stagnate on indefinite systems
  for (const char* pc : {"none", "jacobi", "schwarz"}) {
    // Jacobi needs a positive diagonal and may refuse; the Schwarz blocks are
    // reflected (eq. 14) and stay SPD by design.
    std::unique_ptr<Preconditioner> M;
    std::string error;
    try {
      M = make_preconditioner(pc);
      M->set_mesh_view({&mesh, &dofs});
      if (!M->setup(K)) error = M->last_error();
    } catch (const std::exception& e) {
      error = e.what();
    }
    check_set_up(report, pc, K, error);
    if (!error.empty()) continue;
    Eigen::VectorXd xs = Eigen::VectorXd::Zero(b.size());
    const KrylovResult cg = conjugate_gradient(K, b, xs, *M, opt);
    // The iteration CG stopped at with a breakdown; NaN (fails) when it reported
    // none, which on this matrix means it ran to the limit or "converged" on garbage.
    report.check("solvers.indefinite", fmt::format("cg+{} reports breakdown", pc),
                 cg.breakdown.empty() ? std::numeric_limits<double>::quiet_NaN() : cg.iterations,
                 opt.max_iterations - 1, Compare::AtMost,
                 fmt::format("the iteration of the breakdown, before the limit of {}: CG needs p^T A p > 0 and must say "
                             "so, not return garbage: {}",
                             opt.max_iterations, cg.breakdown.empty() ? "no breakdown reported" : cg.breakdown));
    struct Method {
      const char* name;
      KrylovResult (*run)(const SparseMatrix&, const Eigen::VectorXd&, Eigen::VectorXd&, const Preconditioner&,
                          const KrylovOptions&);
    };
    for (const Method m : {Method{"cr", &conjugate_residual}, Method{"minres", &minres}, Method{"gmres", &gmres}}) {
      xs.setZero(b.size());
      const KrylovResult r = (*m.run)(K, b, xs, *M, opt);
      report.check("solvers.indefinite", fmt::format("{}+{} relative residual", m.name, pc),
                   (b - K * xs).norm() / b.norm(), opt.rtol, Compare::AtMost,
                   fmt::format("requested tolerance; {} iterations{}", r.iterations,
                               r.breakdown.empty() ? "" : ", " + r.breakdown));
    }
  }
}

// Iterations of CG + BoomerAMG over three uniform refinements.
void add_amg_scaling_rows(Report& report) {
  struct Series {
    int order;
    int n0;
  };
  for (const Series s : {Series{1, 3}, Series{2, 2}}) {
    std::vector<int> its;
    std::string sizes;
    try {
      for (int k = 0; k < 4; ++k) {
        const int n = s.n0 << k;
        const ElasticSystem sys = {"", CellType::Tetrahedron, s.order, n};
        auto solver = make_linear_solver("cg+amg");
        solver->set_relative_tolerance(1e-8);
        solver->analyze(sys.body.K);
        solver->factorize(sys.body.K);
        Eigen::VectorXd x;
        solver->solve(sys.b, x);
        its.push_back(solver->last_iterations());
        sizes += fmt::format("{}n={}: {} unknowns {} its", sizes.empty() ? "" : "; ", n, sys.body.K.rows(), its.back());
      }
    } catch (const std::exception& e) {
      // The row it would have measured, unmeasured (NaN fails).
      report.check("solvers.amg_scaling", fmt::format("Tet order {} cg+amg iterations, finest / coarsest", s.order),
                   std::numeric_limits<double>::quiet_NaN(), 1.5, Compare::AtMost, std::string("failed: ") + e.what());
      continue;
    }
    report.check("solvers.amg_scaling", fmt::format("Tet order {} cg+amg iterations, finest / coarsest", s.order),
                 static_cast<double>(its.back()) / its.front(), 1.5, Compare::AtMost,
                 "near mesh-independent AMG convergence, at most 1.5x over "
                 "three refinements; " +
                     sizes);
  }
}

}  // namespace

void add_solver_checks(Report& report) {
  add_spd_rows(report);
  add_preconditioner_rows(report);
  add_indefinite_rows(report);
  add_amg_scaling_rows(report);
}

}  // namespace hofem::verification
