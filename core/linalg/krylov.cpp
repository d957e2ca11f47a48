#include "linalg/krylov.hpp"

#include <Eigen/Dense>
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

namespace hofem {

namespace {

Eigen::VectorXd apply(const LinearOperator& A, const Eigen::VectorXd& x) {
  Eigen::VectorXd y;
  A.multiply(x, y);
  return y;
}

// Every method starts the same way: x sized like b (zero if it was not), and
// ||b|| to divide residuals by (1 for b = 0: the residual itself).
double start(const Eigen::VectorXd& b, Eigen::VectorXd& x) {
  if (x.size() != b.size()) x.setZero(b.size());
  const double n = b.norm();
  return n > 0.0 ? n : 1.0;
}

// Every method ends the same way: the relative residual it reports is the true
// one, ||b - A x|| / ||b||, not the recurrence's (which drifts from it in
// floating point), and convergence means no breakdown and that residual <= rtol.
void finish(KrylovResult& res, const LinearOperator& A, const Eigen::VectorXd& b, const Eigen::VectorXd& x, double bn,
            double rtol) {
  res.relative_residual = (b - apply(A, x)).norm() / bn;
  res.converged = res.breakdown.empty() && res.relative_residual <= rtol;
}

// When the recurrence's residual passes the tolerance, the true one may not have
// (the drift grows with the iteration count and on indefinite systems: measured,
// CR without preconditioner on the indefinite check matrix stopped after 2859
// iterations at a true 1.00003e-8 for rtol 1e-8). Then the iteration restarts from
// the true residual (residual replacement, as in van der Vorst & Ye 2000), at most
// this many times, after which the attainable accuracy is what it is and the
// result says so (converged = false).
constexpr int kMaxResidualReplacements = 5;

/// True once b - A x meets rtol; else r = b - A x (the caller restarts from it), or
/// gives up (true) after kMaxResidualReplacements replacements.
bool confirm_or_replace(const LinearOperator& A, const Eigen::VectorXd& b, const Eigen::VectorXd& x, double bn,
                        double rtol, Eigen::VectorXd& r, KrylovResult& res, int& replacements) {
  r = b - apply(A, x);
  const double true_relative = r.norm() / bn;
  res.history.back() = true_relative;
  return true_relative <= rtol || ++replacements > kMaxResidualReplacements;
}

}  // namespace

// Thesis Algorithm 4 (preconditioned CG).
KrylovResult conjugate_gradient(const LinearOperator& A, const Eigen::VectorXd& b, Eigen::VectorXd& x,
                                const Preconditioner& M, const KrylovOptions& opt) {
  KrylovResult res;
  const double bn = start(b, x);
  Eigen::VectorXd r = b - apply(A, x), z, Ap;
  M.apply(r, z);
  Eigen::VectorXd p = z;
  double rz = r.dot(z);
  res.history.push_back(r.norm() / bn);
  int replacements = 0;
  for (int k = 0; k < opt.max_iterations; ++k) {
    if (res.history.back() <= opt.rtol) {
      if (confirm_or_replace(A, b, x, bn, opt.rtol, r, res, replacements)) break;
      M.apply(r, z);  // restart the directions from the true residual
      p = z;
      rz = r.dot(z);
    }
    A.multiply(p, Ap);
    const double pAp = p.dot(Ap);
    if (!(pAp > 0.0)) {  // negative (or zero) curvature: A is not positive definite
      res.breakdown = fmt::format("CG: p^T A p = {:.3e} <= 0 at iteration {} (matrix not positive definite)", pAp, k);
      break;
    }
    const double alpha = rz / pAp;
    x.noalias() += alpha * p;
    r.noalias() -= alpha * Ap;
    M.apply(r, z);
    const double rz_new = r.dot(z);
    p = z + (rz_new / rz) * p;
    rz = rz_new;
    ++res.iterations;
    res.history.push_back(r.norm() / bn);
  }
  // The recursively updated r drifts from b - A x by ~eps cond(A); the verdict
  // uses the true residual.
  finish(res, A, b, x, bn, opt.rtol);
  return res;
}

// Thesis Algorithm 5 (preconditioned conjugate residuals): minimises the residual
// in the A-norm of the preconditioned system; needs A symmetric, not definite.
KrylovResult conjugate_residual(const LinearOperator& A, const Eigen::VectorXd& b, Eigen::VectorXd& x,
                                const Preconditioner& M, const KrylovOptions& opt) {
  KrylovResult res;
  const double bn = start(b, x);
  Eigen::VectorXd r = b - apply(A, x), z, q;
  M.apply(r, z);  // z = M^-1 r
  Eigen::VectorXd Az = apply(A, z), p = z, Ap = Az;
  double zAz = z.dot(Az);
  res.history.push_back(r.norm() / bn);
  int replacements = 0;
  for (int k = 0; k < opt.max_iterations; ++k) {
    if (res.history.back() <= opt.rtol) {
      if (confirm_or_replace(A, b, x, bn, opt.rtol, r, res, replacements)) break;
      M.apply(r, z);  // restart the directions from the true residual
      A.multiply(z, Az);
      p = z;
      Ap = Az;
      zAz = z.dot(Az);
    }
    M.apply(Ap, q);  // q = M^-1 A p
    const double denom = Ap.dot(q);
    if (denom == 0.0 || !std::isfinite(denom) || zAz == 0.0) {
      res.breakdown = fmt::format("CR: breakdown at iteration {} ((Ap, M^-1 Ap) = {:.3e}, (z, Az) = {:.3e})", k, denom, zAz);
      break;
    }
    const double alpha = zAz / denom;
    x.noalias() += alpha * p;
    r.noalias() -= alpha * Ap;
    z.noalias() -= alpha * q;
    A.multiply(z, Az);
    const double zAz_new = z.dot(Az);
    const double beta = zAz_new / zAz;
    p = z + beta * p;
    Ap = Az + beta * Ap;
    zAz = zAz_new;
    ++res.iterations;
    res.history.push_back(r.norm() / bn);
  }
  finish(res, A, b, x, bn, opt.rtol);
  return res;
}

// Preconditioned MINRES (Paige & Saunders 1975; the recurrences as in Choi,
// Paige & Saunders 2011, Table 2.1). M must be SPD; A symmetric, possibly
// indefinite. The residual norm is the method's own estimate (in the M^-1 norm
// scaled back), checked against the true residual at the end.
KrylovResult minres(const LinearOperator& A, const Eigen::VectorXd& b, Eigen::VectorXd& x, const Preconditioner& M,
                    const KrylovOptions& opt) {
  KrylovResult res;
  const Eigen::Index n = b.size();
  const double bn = start(b, x);
  Eigen::VectorXd r1 = b - apply(A, x), y, r2, v, w = Eigen::VectorXd::Zero(n), w1 = w, w2 = w;
  M.apply(r1, y);
  double beta1 = r1.dot(y);
  res.history.push_back(r1.norm() / bn);
  if (beta1 < 0.0) {
    res.breakdown = "MINRES: preconditioner is not positive definite";
    res.relative_residual = res.history.back();
    return res;
  }
  beta1 = std::sqrt(beta1);
  if (beta1 == 0.0) {
    res.converged = true;
    return res;
  }
  r2 = r1;
  double oldb = 0.0, beta = beta1, dbar = 0.0, epsln = 0.0, phibar = beta1, cs = -1.0, sn = 0.0;
  // The estimate phibar is in the M^-1 norm; scale it to the 2-norm of r by the
  // ratio at the start (exact for M = I) and confirm with the true residual.
  const double scale = res.history.front() / phibar;
  Eigen::VectorXd Av;
  for (int k = 0; k < opt.max_iterations; ++k) {
    // The estimate is exact only for M = I: once it passes, confirm with the true
    // residual (one extra product per iteration from then on) and go on if needed.
    if (phibar * scale <= opt.rtol && (b - apply(A, x)).norm() / bn <= opt.rtol) break;
    const double s = 1.0 / beta;
    v = s * y;
    A.multiply(v, Av);
    if (k > 0) Av -= (beta / oldb) * r1;
    const double alfa = v.dot(Av);
    Av -= (alfa / beta) * r2;
    r1 = r2;
    r2 = Av;
    M.apply(r2, y);
    oldb = beta;
    beta = r2.dot(y);
    if (beta < 0.0) {
      res.breakdown = "MINRES: preconditioner is not positive definite";
      break;
    }
    beta = std::sqrt(beta);
    const double oldeps = epsln;
    const double delta = cs * dbar + sn * alfa;
    const double gbar = sn * dbar - cs * alfa;
    epsln = sn * beta;
    dbar = -cs * beta;
    const double gamma = std::max(std::hypot(gbar, beta), 1e-300);
    cs = gbar / gamma;
    sn = beta / gamma;
    const double phi = cs * phibar;
    phibar = sn * phibar;
    w1 = w2;
    w2 = w;
    w = (v - oldeps * w1 - delta * w2) / gamma;
    x.noalias() += phi * w;
    ++res.iterations;
    res.history.push_back(phibar * scale);
    if (beta == 0.0) break;  // exact Krylov space exhausted: x is the solution
  }
  finish(res, A, b, x, bn, opt.rtol);
  return res;
}

// Thesis Algorithm 6, restarted GMRES(m) with right preconditioning (so the
// monitored residual is the true one), modified Gram–Schmidt and Givens rotations.
KrylovResult gmres(const LinearOperator& A, const Eigen::VectorXd& b, Eigen::VectorXd& x, const Preconditioner& M,
                   const KrylovOptions& opt) {
  KrylovResult res;
  const Eigen::Index n = b.size();
  const double bn = start(b, x);
  const int m = std::max(1, opt.restart);
  Eigen::MatrixXd V(n, m + 1), H = Eigen::MatrixXd::Zero(m + 1, m);
  Eigen::VectorXd cs(m), sn(m), g(m + 1), z, w;
  Eigen::VectorXd r = b - apply(A, x);
  double beta = r.norm();
  res.history.push_back(beta / bn);
  while (res.iterations < opt.max_iterations && res.history.back() > opt.rtol) {
    V.col(0) = r / beta;
    g.setZero();
    g[0] = beta;
    int j = 0;
    for (; j < m && res.iterations < opt.max_iterations; ++j) {
      M.apply(V.col(j), z);
      A.multiply(z, w);
      for (int i = 0; i <= j; ++i) {
        H(i, j) = w.dot(V.col(i));
        w.noalias() -= H(i, j) * V.col(i);
      }
      H(j + 1, j) = w.norm();
      if (H(j + 1, j) > 0.0) V.col(j + 1) = w / H(j + 1, j);
      for (int i = 0; i < j; ++i) {  // apply earlier rotations
        const double t = cs[i] * H(i, j) + sn[i] * H(i + 1, j);
        H(i + 1, j) = -sn[i] * H(i, j) + cs[i] * H(i + 1, j);
        H(i, j) = t;
      }
      const double d = std::hypot(H(j, j), H(j + 1, j));
      if (d == 0.0) {
        res.breakdown = fmt::format("GMRES: breakdown at iteration {} (singular Hessenberg matrix)", res.iterations);
        break;
      }
      cs[j] = H(j, j) / d;
      sn[j] = H(j + 1, j) / d;
      H(j, j) = d;
      H(j + 1, j) = 0.0;
      g[j + 1] = -sn[j] * g[j];
      g[j] = cs[j] * g[j];
      ++res.iterations;
      res.history.push_back(std::fabs(g[j + 1]) / bn);
      if (res.history.back() <= opt.rtol) {
        ++j;
        break;
      }
    }
    if (j == 0) break;
    // x += M^-1 V y with H y = g (upper triangular j x j).
    const Eigen::VectorXd y = H.topLeftCorner(j, j).triangularView<Eigen::Upper>().solve(g.head(j));
    M.apply(V.leftCols(j) * y, z);
    x.noalias() += z;
    r = b - apply(A, x);
    beta = r.norm();
    res.history.back() = beta / bn;  // true residual at the restart
    if (!res.breakdown.empty()) break;
  }
  // r is the true residual of the last restart: no second product needed.
  res.relative_residual = res.history.back();
  res.converged = res.breakdown.empty() && res.relative_residual <= opt.rtol;
  return res;
}

KrylovSolver::KrylovSolver(SolverMethod method, std::unique_ptr<Preconditioner> preconditioner, KrylovOptions options)
    : method_(method), M_(std::move(preconditioner)), options_(options) {
  if (!M_) throw std::invalid_argument("KrylovSolver: no preconditioner (make_identity_preconditioner for none)");
  if (!is_krylov_method(method_))
    throw std::invalid_argument(
        fmt::format("KrylovSolver: '{}' is not a Krylov method (cg, cr, minres, gmres)", method_name(method_)));
  name_ = std::string(method_name(method_)) + "+" + std::string(M_->name());
}

void KrylovSolver::analyze(const SparseMatrix&) { ++analyses_; }

// Set-up reuse (SetupReuse). A preconditioner applies only what its set-up
// stored (pmg its single-precision levels, Schwarz its block inverses, AMG
// hypre's copy), so a reused one is still a fixed SPD operator and CG stays
// valid; the operator of the iterations is always the new matrix. What a stale
// set-up costs is iterations, and the trigger counts them:
//  - Growth: a solve needing more than `growth` x the iterations of the first
//    solve after the set-up ends the reuse.
//  - Amortised: a set-up costs S seconds, an iteration t (both measured on
//    the last set-up and its first solve); the first solve's count b is what a
//    fresh set-up gives. After L solves on one set-up with e_i = k_i - b extra
//    iterations, the cycle has cost S + t (L b + E), E = sum e_i, on average
//    per solve A = (S + t (L b + E)) / L. The reuse ends when the last solve
//    cost more than that average, t k_L > A, i.e. e_L L > S / t + E: the rule
//    that minimises the long-run cost per solve when staleness grows steadily
//    (the renewal argument for replacement policies). A fixed factor cannot
//    be right for both: measured on the Tet10 twisting cylinder (E = 5e6, nu
//    = 0.48, 41.7 k unknowns, 11 steps from rest, CG + pmg): a set-up costs
//    S/t ~ 4-5 iterations against ~30 per solve, so a factor of 1.5 lost
//    (996 iterations and 3 set-ups against 787 and 26: ~+25 % of the solve
//    time for -80 % of the set-ups' ~10 %).
bool KrylovSolver::factorize(const SparseMatrix& A) {
  A_ = &A;
  use_block_ = A.rows() % 3 == 0 && A.rows() == A.cols() && A.isCompressed();
  const std::uint64_t pattern = pattern_fingerprint(A);
  const bool same_pattern = pattern == setup_pattern_ && A.rows() == setup_rows_;
  if (use_block_) {
    if (pattern != block_.source_fingerprint() || block_.rows() != A.rows()) {
      block_ = BlockSparseMatrix<double>(A);
      block_.set_source_fingerprint(pattern);
    } else {
      block_.set_values(A);
    }
  }
  setup_pattern_ = pattern;
  setup_rows_ = A.rows();
  const bool reuse = options_.setup_reuse == SetupReuse::Amortised || options_.setup_reuse == SetupReuse::Growth;
  if (reuse && fixed_iterations_ == 0 && !rebuild_next_ && same_pattern) {
    ++setup_reuses_;
    reused_ = true;
    return true;
  }
  return setup_preconditioner(A);
}

bool KrylovSolver::setup_preconditioner(const SparseMatrix& A) {
  ++factorizations_;
  reused_ = false;
  baseline_iterations_ = -1;
  solves_since_setup_ = 0;
  extra_since_setup_ = 0;
  const auto t0 = std::chrono::steady_clock::now();
  const bool ok = use_block_ ? M_->setup(A, block_) : M_->setup(A);
  last_setup_seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  setup_seconds_ += last_setup_seconds_;
  rebuild_next_ = !ok;
  return ok;
}

void KrylovSolver::iterate(const Eigen::VectorXd& b, Eigen::VectorXd& x) {
  x.setZero(b.size());
  const SparseMatrixOperator sparse(*A_);
  const BlockOperator<double> block(block_);
  const LinearOperator& A = use_block_ ? static_cast<const LinearOperator&>(block) : sparse;
  KrylovOptions options = options_;
  if (fixed_iterations_ > 0) {  // exactly k iterations: no tolerance can stop them earlier
    options.rtol = 0.0;
    options.max_iterations = fixed_iterations_;
  }
  switch (method_) {
    case SolverMethod::Cg: last_ = conjugate_gradient(A, b, x, *M_, options); break;
    case SolverMethod::Cr: last_ = conjugate_residual(A, b, x, *M_, options); break;
    case SolverMethod::Minres: last_ = minres(A, b, x, *M_, options); break;
    default: last_ = gmres(A, b, x, *M_, options); break;  // the constructor admits only these four
  }
}

void KrylovSolver::solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) {
  if (!A_) throw std::logic_error("KrylovSolver::solve before factorize");
  // A fixed budget accepts the iterate it reached; a breakdown (an indefinite
  // system) is still an error.
  const auto accepted = [&] {
    return last_.converged || (fixed_iterations_ > 0 && last_.breakdown.empty() && x.allFinite());
  };
  auto t0 = std::chrono::steady_clock::now();
  iterate(b, x);
  double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  int iterations = last_.iterations;
  // A reused set-up that fails (a stale preconditioner, or an indefinite matrix
  // that a fresh set-up would have refused): once more on a fresh set-up.
  if (!accepted() && reused_) {
    if (!setup_preconditioner(*A_))
      throw std::runtime_error(fmt::format("{}: no convergence on a reused set-up ({} iterations), and a new set-up "
                                           "failed: {}",
                                           name_, iterations, M_->last_error()));
    t0 = std::chrono::steady_clock::now();
    iterate(b, x);
    seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    iterations += last_.iterations;
  }
  const int fresh_iterations = last_.iterations;  // of the last attempt
  if (!accepted()) {
    rebuild_next_ = true;
    throw std::runtime_error(fmt::format("{}: no convergence ({} iterations, relative residual {:.3e}){}{}", name_,
                                         last_.iterations, last_.relative_residual, last_.breakdown.empty() ? "" : ": ",
                                         last_.breakdown));
  }
  last_.iterations = iterations;  // the work of this solve, the retry included
  if (options_.setup_reuse != SetupReuse::Amortised && options_.setup_reuse != SetupReuse::Growth) return;
  if (baseline_iterations_ < 0) {  // the first solve after a set-up (a retried one included)
    baseline_iterations_ = fresh_iterations;
    setup_cost_iterations_ = last_setup_seconds_ / std::max(seconds / std::max(fresh_iterations, 1), 1e-12);
    solves_since_setup_ = 1;
    return;
  }
  ++solves_since_setup_;
  const long long extra = std::max(0, fresh_iterations - baseline_iterations_);
  extra_since_setup_ += extra;
  if (options_.setup_reuse == SetupReuse::Growth)
    rebuild_next_ = fresh_iterations > options_.setup_reuse_growth * std::max(baseline_iterations_, 1);
  else
    rebuild_next_ = static_cast<double>(extra * solves_since_setup_) >
                    setup_cost_iterations_ + static_cast<double>(extra_since_setup_);
}

}  // namespace hofem
