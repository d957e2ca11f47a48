#include "fcm_conditioning_checks.hpp"

#include "dense_eigenvalues.hpp"

#include "assembly/assembler.hpp"
#include "assembly/dof_map.hpp"
#include "embedded/embedded_quadrature.hpp"
#include "embedded/finite_cell_quadrature.hpp"
#include "material/material.hpp"
#include "mesh/box_mesh.hpp"
#include "solver/additive_schwarz.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

namespace hofem::verification {

namespace {

// ---------------------------------------------------------------------------
// The experiment of Longva et al. 2020 §5.4 and its parameters.

constexpr const char* kGroup = "embedded.fig5";
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// Longva et al. 2020 §5.4: Stable Neo-Hookean, E = 3e6 Pa, nu = 0.4, dt = 1/60 s. It gives
// no density; 1000 kg/m^3 is that of soft tissue / rubber-like solids, the kind of
// material E = 3 MPa models. With it dt^2 E / (rho h^2) ~ 7.5 at the cell size h = 1/3
// (30 at Tet10's node spacing): stiffness dominates but mass matters, as in a typical
// backward-Euler step, and the indefinite part of dt^2 K is not hidden by M (A has
// ~10 % negative eigenvalues; each row counts them).
constexpr double kDensity = 1000.0;
constexpr double kDt = 1.0 / 60.0;
constexpr double kStabilisation = 1e-6;    // Longva et al. 2020 §5.3/§5.4
constexpr double kSchwarzFraction = 0.5;   // Longva et al. 2020 §5.2: blocks on cut cells below 0.5-0.7
constexpr double kSchwarzEpsilon = 1e-13;  // Longva et al. 2020 eq. 14

/// Background grid [0, 4/3]^3 with 4 cells a side (cell size 1/3).
Mesh background_mesh(int order) {
  return box_mesh(BoxSpec{{0, 0, 0}, {4.0 / 3, 4.0 / 3, 4.0 / 3}, {4, 4, 4}}, CellType::Tetrahedron, order);
}

/// The embedded box [0, 1 + eps/3]^3: its last background layer is cut to a width
/// eps of a cell in each direction. In the Kuhn split every tetrahedron of the
/// corner cube is a cone from the cube's (0,0,0) corner, so each contains 1/6 of
/// the (eps/3)^3 corner: the smallest volume fraction is eps^3 on tets too.
Mesh embedded_box(double eps) {
  const double top = 1.0 + eps / 3.0;
  return box_mesh(BoxSpec{{0, 0, 0}, {top, top, top}, {3, 3, 3}}, CellType::Tetrahedron, 1);
}

/// x = X + u(X), u = (X, X, -X) (X the first coordinate): F = I + (1,1,-1) e_x^T, det F = 2.
Eigen::VectorXd deformed_positions(const Mesh& mesh) {
  Eigen::VectorXd x(3 * mesh.num_nodes());
  for (int n = 0; n < mesh.num_nodes(); ++n) {
    const Eigen::Vector3d X = mesh.nodes.col(n);
    x.segment<3>(3 * n) = X + Eigen::Vector3d(X.x(), X.x(), -X.x());
  }
  return x;
}

// ---------------------------------------------------------------------------
// Condition numbers. S A has the spectrum of L^T A L for S = L L^T (S SPD).
// A may be indefinite (unprojected Stable Neo-Hookean Hessian), so
// kappa = max |lambda| / min |lambda|, the ratio MINRES' convergence depends on.

enum Preconditioner { kNone, kJacobi, kSchwarz, kNumPreconditioners };
constexpr std::array<const char*, kNumPreconditioners> kPreconditionerNames{"none", "jacobi", "schwarz"};

struct Spectrum {
  bool computed = false;  ///< false: not asked for at this level (no row)
  double kappa = kNaN;
  double smallest = kNaN, largest = kNaN;  ///< min and max |lambda|
  int negative = 0, size = 0;
  double seconds = 0.0;  ///< forming L^T A L and the eigen-solve
  std::string error;     ///< why there is no spectrum (kappa NaN)
};

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

/// Spectrum of the symmetric part of B (eigenvalues only).
Spectrum symmetric_spectrum(const Eigen::MatrixXd& B) {
  Spectrum s;
  s.computed = true;
  s.size = static_cast<int>(B.rows());
  const std::optional<Eigen::VectorXd> eigenvalues = symmetric_eigenvalues(0.5 * (B + B.transpose()));
  if (!eigenvalues) {
    s.error = "the symmetric eigen-solver (LAPACK dsyevd) did not converge";
    return s;
  }
  const Eigen::VectorXd& lambda = *eigenvalues;
  s.negative = static_cast<int>((lambda.array() < 0.0).count());
  s.smallest = lambda.cwiseAbs().minCoeff();
  s.largest = lambda.cwiseAbs().maxCoeff();
  s.kappa = s.largest / s.smallest;  // +inf for an exactly singular matrix: a result, not an error
  return s;
}

Spectrum unpreconditioned_spectrum(const SparseMatrix& A) {
  const auto t0 = std::chrono::steady_clock::now();
  Spectrum s = symmetric_spectrum(Eigen::MatrixXd(A));
  s.seconds = seconds_since(t0);
  return s;
}

/// S = diag(1 / |A_ii|): L = S^(1/2) is diagonal (|A_ii| as the Schwarz
/// preconditioner's uncovered DOFs use, positive even if A is indefinite).
Spectrum jacobi_spectrum(const SparseMatrix& A) {
  const auto t0 = std::chrono::steady_clock::now();
  const Eigen::VectorXd d = Eigen::VectorXd(A.diagonal()).cwiseAbs().cwiseSqrt().cwiseInverse();
  Spectrum s = symmetric_spectrum(d.asDiagonal() * Eigen::MatrixXd(A) * d.asDiagonal());
  s.seconds = seconds_since(t0);
  return s;
}

/// S of eq. 13-14 as a dense matrix: the blocks S_K scattered to their free DOFs
/// plus 1 / |A_ii| on the DOFs no block covers (O(blocks x 30^2), where n calls of
/// apply() on unit vectors would cost n thread fork-joins); compared with apply()
/// on a random vector so the dense S is the operator the solvers use.
Spectrum schwarz_spectrum(const SparseMatrix& A, const Mesh& mesh, const DofMap& dofs, const std::vector<int>& blocks) {
  Spectrum s;
  s.computed = true;
  AdditiveSchwarzOptions options;
  options.elements = blocks;
  options.epsilon = kSchwarzEpsilon;
  AdditiveSchwarzPreconditioner P(options);
  P.set_mesh_view(MeshView{&mesh, &dofs});
  if (!P.setup(A)) {
    s.error = "Additive-Schwarz setup failed: " + P.last_error();
    return s;
  }
  const auto t0 = std::chrono::steady_clock::now();
  const Eigen::Index n = A.rows();
  Eigen::MatrixXd S = Eigen::MatrixXd::Zero(n, n);
  std::vector<char> covered(n, 0);
  for (int b = 0; b < P.num_blocks(); ++b) {
    const std::span<const int> d = P.block_dofs(b);
    const auto Sb = P.block_inverse(b);
    for (size_t j = 0; j < d.size(); ++j) {
      covered[d[j]] = 1;
      for (size_t i = 0; i < d.size(); ++i) S(d[i], d[j]) += Sb(i, j);
    }
  }
  for (Eigen::Index i = 0; i < n; ++i)
    if (!covered[i]) S(i, i) = 1.0 / std::abs(A.coeff(i, i));
  const Eigen::VectorXd r = Eigen::VectorXd::Random(n);
  Eigen::VectorXd z;
  P.apply(r, z);
  if (!((S * r - z).norm() <= 1e-12 * z.norm())) {
    s.error = fmt::format("the dense S differs from apply() by {:.2e} (relative)", (S * r - z).norm() / z.norm());
    return s;
  }
  const Eigen::LLT<Eigen::MatrixXd> llt(0.5 * (S + S.transpose()));
  if (llt.info() != Eigen::Success) {
    // Longva et al. 2020 §5.3: without stabilisation the blocks become numerically singular and
    // eq. 14 replaces their smallest eigenvalues by eps / lambda_max, which rounding
    // swamps: S is then not numerically SPD and S A has no computable spectrum.
    const Spectrum of_S = symmetric_spectrum(S);
    s.kappa = std::numeric_limits<double>::infinity();
    s.error = fmt::format(
        "breakdown: S is not numerically positive definite (Cholesky fails; S has {} negative "
        "eigenvalues, |lambda(S)| in [{:.3e}, {:.3e}]); kappa recorded as +inf",
        of_S.negative, of_S.smallest, of_S.largest);
    s.seconds = seconds_since(t0);
    return s;
  }
  const Eigen::MatrixXd L = llt.matrixL();
  const Eigen::MatrixXd AL = A * L;
  s = symmetric_spectrum(L.transpose().triangularView<Eigen::Upper>() * AL);
  s.seconds = seconds_since(t0);
  return s;
}

// ---------------------------------------------------------------------------
// One (order, eps) case: the cut quadrature once, then the system without and
// with stabilisation, and the spectra asked for.

/// Which spectra to compute, indexed by Preconditioner (each Tet10 one costs ~2 s).
struct Variants {
  std::array<bool, kNumPreconditioners> plain{true, true, true};       ///< without stabilisation
  std::array<bool, kNumPreconditioners> stabilised{true, true, true};  ///< with
};

struct CaseResult {
  int order = 1;
  double eps = 1.0;
  double min_fraction = 1.0;  ///< smallest volume fraction over cut cells (1: none is cut)
  int cut_cells = 0, schwarz_blocks = 0, free_dofs = 0, constrained_unsupported = 0;
  double quadrature_seconds = 0.0;
  std::array<Spectrum, kNumPreconditioners> plain, stabilised;  ///< without / with §5.3 stabilisation
};

CaseResult run_case(int order, double eps, const Material& material, const Variants& variants) {
  CaseResult r;
  r.order = order;
  r.eps = eps;
  const Mesh background = background_mesh(order);
  const Mesh geometry = embedded_box(eps);
  const auto t0 = std::chrono::steady_clock::now();
  const CellQuadrature cut = finite_cell_quadrature(background, mesh_tetrahedra(geometry));  // simplified rules
  r.quadrature_seconds = seconds_since(t0);

  std::vector<int> blocks;
  for (int e = 0; e < background.num_elements(); ++e) {
    const double f = cut.volume_fraction[e];
    if (f <= 0.0 || f >= 1.0 - 1e-12) continue;  // outside or uncut (finite_cell_quadrature's own test)
    ++r.cut_cells;
    r.min_fraction = std::min(r.min_fraction, f);
    if (f < kSchwarzFraction) blocks.push_back(e);
  }
  r.schwarz_blocks = static_cast<int>(blocks.size());
  const Eigen::VectorXd x = deformed_positions(background);

  for (bool stabilise : {false, true}) {
    auto& spectra = stabilise ? r.stabilised : r.plain;
    if (stabilise && r.cut_cells == 0) {
      spectra = r.plain;  // nothing to stabilise (eps = 1): the same system
      continue;
    }
    std::array<bool, kNumPreconditioners> wanted = stabilise ? variants.stabilised : variants.plain;
    if (r.cut_cells == 0)  // this system serves both rows
      for (int p = 0; p < kNumPreconditioners; ++p) wanted[p] = wanted[p] || variants.stabilised[p];
    // No block selected (eps = 1): eq. 13's diagonal on every DOF, i.e. Jacobi.
    // (An empty element list would mean "all elements" to the preconditioner.)
    const bool schwarz_is_jacobi = blocks.empty();
    if (wanted[kSchwarz] && schwarz_is_jacobi) wanted[kJacobi] = true;
    if (!wanted[kNone] && !wanted[kJacobi] && !wanted[kSchwarz]) continue;

    CellQuadrature cells = cut;
    if (stabilise) stabilise_finite_cells(background, cells, {/*drop_fraction=*/0.0, kStabilisation});
    const ElementRules rules = cells.element_rules();
    std::vector<int> fixed = background.node_set("xmin");
    const std::vector<int> unsupported = unsupported_nodes(background, rules);
    r.constrained_unsupported = static_cast<int>(unsupported.size());
    fixed.insert(fixed.end(), unsupported.begin(), unsupported.end());
    std::sort(fixed.begin(), fixed.end());
    fixed.erase(std::unique(fixed.begin(), fixed.end()), fixed.end());
    const DofMap dofs(background.num_nodes(), fixed);
    r.free_dofs = dofs.num_free();

    Assembler assembler(background, dofs);
    assembler.set_element_rules(rules);
    SparseMatrix K = assembler.new_matrix();
    Eigen::VectorXd g;
    assembler.hessian(material, x, g, K, /*project=*/false);
    const SparseMatrix A = assembler.mass_matrix(kDensity, 2 * order) + (kDt * kDt) * K;

    if (wanted[kNone]) spectra[kNone] = unpreconditioned_spectrum(A);
    if (wanted[kJacobi]) spectra[kJacobi] = jacobi_spectrum(A);
    if (wanted[kSchwarz])
      spectra[kSchwarz] = schwarz_is_jacobi ? spectra[kJacobi] : schwarz_spectrum(A, background, dofs, blocks);
  }
  return r;
}

// ---------------------------------------------------------------------------
// Sweeps per level, rows and checks.

struct Sweep {
  int order;
  std::vector<double> eps;  ///< decreasing, starting at 1 (the uncut reference)
  Variants variants;
};

std::vector<Sweep> sweeps(const std::string& level) {
  const std::vector<double> all{1.0, 0.5, 0.2, 0.1, 0.05, 0.02, 0.01, 3e-3, 1e-3};
  if (level == "full") return {{1, all, {}}, {2, all, {}}};
  if (level == "ci") {
    // Tet10 has 1944 free DOFs: each dense eigen-solve takes ~2 s here (the
    // "seconds" of every row), so CI computes only what its checks read: Jacobi
    // without stabilisation (b) and Schwarz with it (a), at eps = 1, the first eps
    // with every cut cell a block (0.2) and 0.01.
    Variants tet10;
    tet10.plain = {false, true, false};
    tet10.stabilised = {false, false, true};
    return {{1, all, {}}, {2, {1.0, 0.2, 0.01}, tet10}};
  }
  throw std::invalid_argument(fmt::format("fcm conditioning: unknown level '{}' (valid: ci, full)", level));
}

std::string cell_name(int order) { return order == 1 ? "tet4" : order == 2 ? "tet10" : fmt::format("tet-p{}", order); }

void record_case(Report& report, const CaseResult& r) {
  const std::string cell = cell_name(r.order);
  report.measure(kGroup, fmt::format("{} smallest volume fraction eps={:g}", cell, r.eps), r.min_fraction,
                 fmt::format("{} cut cells, {} Schwarz blocks (fraction < {}), {} free DOFs, {} unsupported nodes "
                             "constrained; quadrature {:.2f} s",
                             r.cut_cells, r.schwarz_blocks, kSchwarzFraction, r.free_dofs, r.constrained_unsupported,
                             r.quadrature_seconds));
  for (bool stabilised : {false, true}) {
    const auto& spectra = stabilised ? r.stabilised : r.plain;
    for (int p = 0; p < kNumPreconditioners; ++p) {
      const Spectrum& s = spectra[p];
      if (!s.computed) continue;
      report.measure(kGroup,
                     fmt::format("{} {} {} eps={:g} fraction={:.3g}", cell, kPreconditionerNames[p],
                                 stabilised ? "stabilised" : "unstabilised", r.eps, r.min_fraction),
                     s.kappa,
                     s.error.empty()
                         ? fmt::format("kappa of S A = max|lambda| / min|lambda| (A indefinite); |lambda| in [{:.3e}, "
                                       "{:.3e}], {} of {} negative; {:.2f} s",
                                       s.smallest, s.largest, s.negative, s.size, s.seconds)
                         : s.error);
    }
  }
  if (r.eps < 1.0) {
    report.check(kGroup, fmt::format("{} |smallest volume fraction - eps^3|, eps={:g}", cell, r.eps),
                 std::abs(r.min_fraction - r.eps * r.eps * r.eps), 1e-13, Compare::AtMost,
                 "the corner cube's Kuhn tets are cones from its (0,0,0) corner, so each holds 1/6 of the "
                 "(eps h)^3 corner: fraction eps^3 exactly. The computed fraction sums clipped-piece volumes "
                 "formed from coordinates of size h, so its rounding is absolute, ~1e-16 per piece of the cell "
                 "volume (not relative to the tiny piece): 1e-13 ~ 1000 ulp of the cell");
  }
}

/// Largest kappa over the cases and the eps where it occurs (kappa NaN if a case
/// has no spectrum, so the check fails).
struct Worst {
  double kappa = 0.0, eps = kNaN;
};
Worst max_kappa(std::span<const CaseResult> cases, bool stabilised, Preconditioner p) {
  Worst worst;
  for (const CaseResult& r : cases) {
    const double k = (stabilised ? r.stabilised : r.plain)[p].kappa;
    if (std::isnan(k)) return {kNaN, r.eps};
    if (k > worst.kappa) worst = {k, r.eps};
  }
  return worst;
}

bool computed(const std::vector<CaseResult>& results, bool stabilised, Preconditioner p) {
  return std::all_of(results.begin(), results.end(),
                     [&](const CaseResult& r) { return (stabilised ? r.stabilised : r.plain)[p].computed; });
}

void check_sweep(Report& report, const std::vector<CaseResult>& results) {
  const CaseResult& uncut = results.front();
  const CaseResult& smallest = results.back();
  const std::string cell = cell_name(uncut.order);

  // (a) Additive Schwarz with stabilisation stays bounded as eps -> 0. Reference:
  // the first eps at which every cut cell is a block; from there on the
  // preconditioner has a fixed structure (at eps = 1 nothing is cut and it is Jacobi).
  const auto first_full = std::find_if(results.begin(), results.end(), [](const CaseResult& r) {
    return r.cut_cells > 0 && r.schwarz_blocks == r.cut_cells;
  });
  if (first_full != results.end() && computed(results, true, kSchwarz)) {
    const std::span<const CaseResult> tail(&*first_full, static_cast<size_t>(results.end() - first_full));
    const double reference = first_full->stabilised[kSchwarz].kappa;
    const Worst worst = max_kappa(tail, true, kSchwarz);
    report.check(
        kGroup,
        fmt::format("{} schwarz stabilised: max kappa / kappa(eps={:g}), eps {:g}..{:g}", cell, first_full->eps,
                    first_full->eps, smallest.eps),
        worst.kappa / reference, 10.0, Compare::AtMost,
        fmt::format(
            "max at eps={:g}; kappa(eps={:g}) = {:.3e}, the first eps with every cut cell a block (kappa(eps=1) = "
            "{:.3e}: no cut cell, Schwarz = Jacobi, a different operator). The blocks invert each cut cell's "
            "coupling exactly and the 1e-6 stabilisation keeps every cut block from becoming singular, so as "
            "eps -> 0 kappa tends to a finite limit; what changes is O(1) (the body shrinks from 1 + {:g}/3 to 1, "
            "and zero crossings of the indefinite Hessian's eigenvalues move). 10: less than a decade, where every "
            "failure mode grows like a power of 1/eps (Jacobi on Tet10: ~eps^-2, 1e4-1e5 over this range)",
            worst.eps, first_full->eps, reference, uncut.stabilised[kSchwarz].kappa, first_full->eps));
  }

  // (b) Tet10 without stabilisation: the ill-conditioning is real (Longva et al. 2020 §5.1).
  if (uncut.order >= 2) {
    for (Preconditioner p : {kNone, kJacobi}) {
      if (!uncut.plain[p].computed || !smallest.plain[p].computed) continue;
      report.check(kGroup,
                   fmt::format("{} {} unstabilised: kappa(eps={:g}) / kappa(eps=1)", cell, kPreconditionerNames[p],
                               smallest.eps),
                   smallest.plain[p].kappa / uncut.plain[p].kappa, 1.0 / smallest.eps, Compare::AtLeast,
                   fmt::format("Longva et al. 2020 §5.1: on a cut of width eps the scaled quadratic basis functions are nearly "
                               "dependent (on [0, eps], N1 + 4 N2 = 4 x^2 is ~eps smaller than N1 and N2), so the "
                               "smallest eigenvalue of the Jacobi-scaled matrix falls like eps^2 and kappa grows "
                               "like eps^-2 (faster unscaled); requiring 1/eps = {:g}, half that exponent, "
                               "separates growth from any bounded kappa",
                               1.0 / smallest.eps));
    }
  }

  // (c) Tet4: Jacobi alone suffices without stabilisation (Longva et al. 2020 §5.3-5.4).
  if (uncut.order == 1 && computed(results, false, kJacobi)) {
    const double jacobi = uncut.plain[kJacobi].kappa;
    const Worst worst = max_kappa(results, false, kJacobi);
    report.check(
        kGroup,
        fmt::format("{} jacobi unstabilised: max kappa / kappa(eps=1), eps {:g}..{:g}", cell, uncut.eps, smallest.eps),
        worst.kappa / jacobi, 10.0, Compare::AtMost,
        fmt::format(
            "max at eps={:g}; kappa(eps=1) = {:.3e} (the same preconditioner at every eps). On a cut of width eps "
            "the linear basis functions are ~1 and ~x/eps-like: diagonal scaling leaves them well "
            "conditioned for any eps (Longva et al. 2020 §5.1), so only the O(1) changes of check (a) remain; "
            "10 as there",
            worst.eps, jacobi));
  }
}

/// Smallest eigenvalue of the symmetric part of dP/dF at the experiment's F: negative
/// means the unprojected Hessian, hence A, can be indefinite.
double smallest_tangent_eigenvalue(const Material& material) {
  Mat3 F = Mat3::Identity();
  F.col(0) += Eigen::Vector3d(1.0, 1.0, -1.0);
  const Mat9 D = material.stress_derivative(F);
  return Eigen::SelfAdjointEigenSolver<Mat9>(0.5 * (D + D.transpose()), Eigen::EigenvaluesOnly).eigenvalues()[0];
}

}  // namespace

void add_fcm_conditioning_checks(Report& report, const std::string& level) {
  const auto t0 = std::chrono::steady_clock::now();
  const std::vector<Sweep> plan = sweeps(level);  // throws on an unknown level before any work
  const auto material = make_material("stable-neohookean", LameParameters::from_young_poisson(3e6, 0.4));
  const double tangent = smallest_tangent_eigenvalue(*material);
  report.measure(kGroup, "stable-neohookean smallest eigenvalue of sym dP/dF at F = I + (1,1,-1) e_x^T", tangent,
                 tangent < 0.0 ? "negative: the unprojected Hessian is indefinite at this deformation (det F = 2), so "
                                 "A = M + dt^2 K may have negative eigenvalues (each kappa row counts them); kappa is "
                                 "therefore max|lambda| / min|lambda|, the ratio MINRES depends on"
                               : "non-negative: A = M + dt^2 K is positive definite");
  for (const Sweep& sweep : plan) {
    std::vector<CaseResult> results;
    for (double eps : sweep.eps) {
      results.push_back(run_case(sweep.order, eps, *material, sweep.variants));
      record_case(report, results.back());
    }
    check_sweep(report, results);
  }
  report.measure(kGroup, fmt::format("runtime seconds level={}", level), seconds_since(t0),
                 "the whole group on this machine (dense eigen-solves dominate)");
}

}  // namespace hofem::verification
