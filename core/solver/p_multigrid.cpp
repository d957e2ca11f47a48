#include "solver/p_multigrid.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

// Defaults (PMultigridOptions), measured 2026-11-22 on this project's machine
// (2 vCPU with AVX-512, shared/machine.md; the machine was shared with other
// builds, so each number is the best of 2 runs taken only when both cores were
// idle before and after, and still varies by ~15 % between sessions).
// Linear-elastic unit cube (E = 1, nu = 0.3) clamped at x = 0, b_i = sin(0.37 i)
// + 0.1, CG from zero to ||r|| <= 1e-8 ||b||. Seconds, wall clock, "2 threads /
// 1 thread". pmg "setup" is a re-setup on a known pattern (every Newton iteration
// after the first); cholmod's is analysis + factorisation.
//
//                        P2 n=12 N=45,000 nnz 3.6M      P3 n=8 N=45,000 nnz 6.0M
//                        it  setup      solve           it  setup      solve
//   cholmod               -  3.71/6.34  0.04/0.05        -  4.10/6.21  0.04/0.06
//   cg+jacobi           524  0.00/0.00  2.34/3.27      828  0.00/0.01  9.61/9.88
//   cg+block-jacobi     584  0.01/0.01  2.95/3.21      764  0.02/0.02  10.96/9.23
//   cg+ic0              227  0.59/0.64  4.01/4.71      262  8.19/6.07  7.56/6.60
//   pmg chebyshev-2      15  0.18/0.33  0.56/0.66       24  0.24/0.31  1.28/1.79
//   pmg chebyshev-3 *    12  0.15/0.32  0.38/0.77       18  0.26/0.38  1.32/2.03
//   pmg chebyshev-4      10  0.21/0.36  0.42/0.59       15  0.24/0.39  1.26/2.17
//   pmg sgs, 1 sweep     16  0.14/0.21  0.75/0.74       30  0.15/0.16  2.10/1.82
//   pmg sgs, 2 sweeps    11  0.17/0.18  0.74/0.65       18  0.12/0.16  1.63/1.77
//
//                        P2 n=16 N=104,544 nnz 8.5M     P3 n=10 N=86,490 nnz 11.7M
//   cholmod               -  11.2/20.1  0.11/0.14        -  8.93/18.2  0.08/0.12
//   cg+jacobi           815  0.01/0.01  12.4/14.1      986  0.01/0.01  23.6/22.7
//   cg+block-jacobi     785  0.02/0.02  15.7/12.3      955  0.04/0.03  24.7/23.7
//   cg+ic0              323  1.33/1.14  13.2/12.4      423  9.82/8.61  24.8/21.5
//   pmg chebyshev-2      15  0.39/0.74  1.17/1.44       24  0.35/0.53  2.37/3.13
//   pmg chebyshev-3 *    12  0.46/0.71  1.11/1.58       18  0.41/0.80  2.09/3.91
//   pmg chebyshev-4      10  0.42/0.86  1.11/1.68       15  0.38/0.52  2.28/3.31
//   pmg sgs, 1 sweep     16  0.29/0.56  1.29/1.38       30  0.24/0.31  3.82/3.51
//   pmg sgs, 2 sweeps    11  0.33/0.53  1.41/1.45       18  0.22/0.33  3.42/3.48
//
//   Hex20 n=10 (N=13,860), 2 threads: cholmod 0.71 + 0.01; cg+jacobi 427 it, 1.04;
//   cg+ic0 151 it, 0.72 + 0.70; pmg chebyshev-3 10 it, 0.07 + 0.19; chebyshev-2
//   14 it, 0.07 + 0.25; sgs 1 sweep 18 it, 0.06 + 0.31.
//
// Choice (*): Chebyshev, degree 3, nodal 3x3 block scaling. On 2 threads (the
// default here) it is as fast as the best symmetric Gauss–Seidel (P2 n=16, where
// the products are memory-bound) to 1.7x faster (P2 n=12, in cache), as GS sweeps
// are serial; on 1 thread the two are within ~15 %. Degrees 2-4 differ by less than
// the noise (P2 leans to 2, P3 to 4); 3 is the middle. Point-Jacobi scaling: same
// or one more iteration, up to 20 % slower. Lanczos: 12 steps put lambda_max
// within 1 % of its 100-step value (6 steps: 5 % low), covered by the 1.2 safety
// factor; smoothing range 20 took the fewest iterations of 5, 10, 20, 40 (as in
// deal.II step-75). Against the baselines (2 threads) pmg is 2.6-7x faster than
// CHOLMOD and 4-9x faster than the best of cg+jacobi / block-jacobi / ic0, and its
// iteration count does not grow with N while theirs does.

namespace hofem {

namespace {

// Matrices with fewer nonzeros than this are smoothed serially: each OpenMP
// region ends in a barrier (microseconds on idle cores, a scheduler time slice on
// busy ones), which 2e5 nonzeros (~0.1-0.2 ms of products) amortise.
constexpr std::int64_t kParallelNonzeros = 200000;


}  // namespace

PMultigridPreconditioner::PMultigridPreconditioner(PMultigridOptions options)
    : options_(options), coarse_(make_linear_solver("cholmod")) {
  if (options_.chebyshev_degree < 1 || !(options_.smoothing_range > 1.0) || !(options_.eigenvalue_safety >= 1.0) ||
      options_.gauss_seidel_sweeps < 1)
    throw std::invalid_argument(
        "pmg: needs chebyshev_degree >= 1, smoothing_range > 1, eigenvalue_safety >= 1, "
        "gauss_seidel_sweeps >= 1");
}

bool PMultigridPreconditioner::setup(const SparseMatrix& A) {
  A_ = nullptr;
  if (!discretization_.valid()) {
    error_ = "pmg: needs the mesh and DOF map (set_discretization) before setup";
    return false;
  }
  const Mesh& mesh = *discretization_.mesh;
  if (mesh.order < 2) {
    error_ = fmt::format(
        "pmg needs element order >= 2 (the mesh is order {}, there is no coarser p level; use amg or ic0)", mesh.order);
    return false;
  }
  if (A.rows() != discretization_.dofs->num_free() || A.cols() != A.rows() || !A.isCompressed()) {
    error_ = fmt::format("pmg: matrix is {}x{} (compressed: {}), the DOF map has {} free DOFs", A.rows(), A.cols(),
                         A.isCompressed(), discretization_.dofs->num_free());
    return false;
  }
  if (!prepare_levels(A) || !build_scaling(A)) return false;
  parallel_ = A.nonZeros() >= kParallelNonzeros;
  if (options_.smoother == PMultigridOptions::Smoother::Chebyshev) estimate_lambda_max(A);
  const Eigen::Index n = A.rows();
  res_.setZero(n);
  d_.setZero(n);
  d_next_.setZero(n);
  rc_.setZero(coarse_size());
  xc_.setZero(coarse_size());
  A_ = &A;
  return true;
}

// The coarse level: P once per discretization, the Galerkin pattern and CHOLMOD's
// symbolic analysis once per pattern, values and numeric factorisation every time.
bool PMultigridPreconditioner::prepare_levels(const SparseMatrix& A) {
  const DofMap& dofs = *discretization_.dofs;
  bool new_pattern = false;
  if (mesh_for_ != discretization_.mesh || dofs_for_ != &dofs) {
    try {
      transfer_ = build_p_prolongation(*discretization_.mesh, dofs);
    } catch (const std::invalid_argument& e) {
      error_ = std::string("pmg: ") + e.what();
      return false;
    }
    mesh_for_ = discretization_.mesh;
    dofs_for_ = &dofs;
    new_pattern = true;
    // Blocks: a node's free components are consecutive in the free numbering
    // (DofMap numbers free DOFs in global order, 3 * node + component).
    block_start_.assign(1, 0);
    const std::vector<int>& free = dofs.free_dofs();
    for (size_t i = 1; i <= free.size(); ++i)
      if (i == free.size() || !options_.block_scaling || free[i] / 3 != free[i - 1] / 3)
        block_start_.push_back(static_cast<Eigen::Index>(i));
  }
  const std::uint64_t hash = pattern_fingerprint(A);
  if (new_pattern || hash != pattern_hash_ || !galerkin_.analyzed()) {
    galerkin_.analyze(A, transfer_);
    Ac_ = galerkin_.zero_matrix();
    pattern_hash_ = hash;
    new_pattern = true;
  }
  if (coarse_size() == 0) return true;  // every vertex constrained: smoothing only
  galerkin_.compute(A, transfer_, Ac_);
  // CHOLMOD re-analyses by itself when P^T A P has a new pattern.
  if (!coarse_->factorize(Ac_)) {
    error_ = "pmg: coarse operator P^T A P is not positive definite (A is not SPD)";
    return false;
  }
  return true;
}

// D_b^-1 for every block, from A's diagonal blocks (SPD when A is).
bool PMultigridPreconditioner::build_scaling(const SparseMatrix& A) {
  const Eigen::Index nb = static_cast<Eigen::Index>(block_start_.size()) - 1;
  block_inverse_.resize(nb);
  for (Eigen::Index b = 0; b < nb; ++b) {
    const Eigen::Index s0 = block_start_[b], s = block_start_[b + 1] - s0;
    Eigen::Matrix3d D = Eigen::Matrix3d::Identity();
    for (Eigen::Index c = 0; c < s; ++c)
      for (SparseMatrix::InnerIterator it(A, s0 + c); it; ++it)
        if (it.row() >= s0 && it.row() < s0 + s) D(it.row() - s0, c) = it.value();
    Eigen::LLT<Eigen::Matrix3d> llt(D);
    if (llt.info() != Eigen::Success) {
      error_ = fmt::format("pmg: diagonal block at free DOF {} is not positive definite", s0);
      return false;
    }
    block_inverse_[b] = llt.solve(Eigen::Matrix3d::Identity());
  }
  return true;
}

void PMultigridPreconditioner::scale(const double* in, double* out, Eigen::Index b) const {
  const Eigen::Index s0 = block_start_[b], s = block_start_[b + 1] - s0;
  const Eigen::Matrix3d& Di = block_inverse_[b];
  if (s == 3) {
    Eigen::Map<Eigen::Vector3d>(out + s0) = Di * Eigen::Map<const Eigen::Vector3d>(in + s0);
    return;
  }
  for (Eigen::Index i = 0; i < s; ++i) {
    double v = 0.0;
    for (Eigen::Index j = 0; j < s; ++j) v += Di(i, j) * in[s0 + j];
    out[s0 + i] = v;
  }
}

// Row i of the symmetric A is its column i: a dot product over one column, so
// rows are independent and loops over them run in parallel (Eigen's column-major
// product would scatter, serially).
double PMultigridPreconditioner::row_dot(Eigen::Index i, const double* x) const {
  const std::int64_t* outer = A_->outerIndexPtr();
  const std::int64_t* inner = A_->innerIndexPtr();
  const double* val = A_->valuePtr();
  double s = 0.0;
  for (std::int64_t q = outer[i]; q < outer[i + 1]; ++q) s += val[q] * x[inner[q]];
  return s;
}

void PMultigridPreconditioner::residual(const Eigen::VectorXd& r, const Eigen::VectorXd& z,
                                        Eigen::VectorXd& res) const {
  const Eigen::Index n = r.size();
#pragma omp parallel for schedule(static) if (parallel_)
  for (Eigen::Index i = 0; i < n; ++i) res[i] = r[i] - row_dot(i, z.data());
}

// Lanczos estimate of lambda_max(D^-1 A) from the CG coefficients (the Lanczos
// tridiagonal T: T_jj = 1/alpha_j + beta_{j-1}/alpha_{j-1}, T_{j,j+1} = sqrt(beta_j)/alpha_j),
// as deal.II's PreconditionChebyshev does. Ritz values approach lambda_max from
// below, hence the safety factor. Start: a fixed pseudo-random vector, so setups
// are reproducible and no smooth mode is missed.
void PMultigridPreconditioner::estimate_lambda_max(const SparseMatrix& A) {
  const Eigen::Index n = A.rows(), nb = static_cast<Eigen::Index>(block_start_.size()) - 1;
  A_ = &A;
  Eigen::VectorXd r(n), z(n), p, q(n);
  std::uint64_t s = 88172645463325252ull;
  for (Eigen::Index i = 0; i < n; ++i) {
    s ^= s << 13, s ^= s >> 7, s ^= s << 17;  // xorshift64
    r[i] = static_cast<double>(s >> 11) * 0x1.0p-53 - 0.5;
  }
  for (Eigen::Index b = 0; b < nb; ++b) scale(r.data(), z.data(), b);
  p = z;
  double rz = r.dot(z), alpha_prev = 1.0, beta_prev = 0.0;
  const int m = std::max(1, options_.eigenvalue_iterations);
  Eigen::VectorXd diag = Eigen::VectorXd::Zero(m), off = Eigen::VectorXd::Zero(m);
  int k = 0;
  for (; k < m; ++k) {
#pragma omp parallel for schedule(static) if (parallel_)
    for (Eigen::Index i = 0; i < n; ++i) q[i] = row_dot(i, p.data());  // q = A p
    const double pAp = p.dot(q);
    if (!(pAp > 0.0) || !(rz > 0.0)) break;
    const double alpha = rz / pAp;
    r.noalias() -= alpha * q;
    for (Eigen::Index b = 0; b < nb; ++b) scale(r.data(), z.data(), b);
    const double rz_new = r.dot(z), beta = rz_new / rz;
    diag[k] = 1.0 / alpha + (k > 0 ? beta_prev / alpha_prev : 0.0);
    off[k] = std::sqrt(std::max(beta, 0.0)) / alpha;
    p = z + beta * p;
    rz = rz_new;
    alpha_prev = alpha;
    beta_prev = beta;
  }
  double est = 1.0;  // D^-1 A has lambda_max >= 1 (its diagonal blocks are I)
  if (k > 0) {
    Eigen::MatrixXd T = Eigen::MatrixXd::Zero(k, k);
    for (int j = 0; j < k; ++j) {
      T(j, j) = diag[j];
      if (j + 1 < k) T(j, j + 1) = T(j + 1, j) = off[j];
    }
    est = std::max(est,
                   Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(T, Eigen::EigenvaluesOnly).eigenvalues().maxCoeff());
  }
  lambda_max_ = options_.eigenvalue_safety * est;
}

// Chebyshev smoothing (Saad, Iterative Methods, Alg. 12.1, with D^-1): on entry
// res_ = b - A z; z gains a degree-k polynomial in D^-1 A applied to D^-1 res_.
// With final_residual, res_ is left as the residual of the new z.
void PMultigridPreconditioner::chebyshev(Eigen::VectorXd& z, bool final_residual) const {
  const double upper = lambda_max_, lower = lambda_max_ / options_.smoothing_range;
  const double theta = 0.5 * (upper + lower), delta = 0.5 * (upper - lower), sigma = theta / delta;
  double rho = 1.0 / sigma;
  const Eigen::Index nb = static_cast<Eigen::Index>(block_start_.size()) - 1;
  double* d = d_.data();
  double* dn = d_next_.data();
  double* res = res_.data();
  double* x = z.data();
#pragma omp parallel for schedule(static) if (parallel_)
  for (Eigen::Index b = 0; b < nb; ++b) {
    scale(res, d, b);
    for (Eigen::Index i = block_start_[b]; i < block_start_[b + 1]; ++i) {
      d[i] /= theta;
      x[i] += d[i];
    }
  }
  for (int k = 1; k < options_.chebyshev_degree; ++k) {
    const double rho_next = 1.0 / (2.0 * sigma - rho), c_old = rho_next * rho, c_res = 2.0 * rho_next / delta;
    // One pass: res -= A d on a block's rows, then that block's new direction.
#pragma omp parallel for schedule(static) if (parallel_)
    for (Eigen::Index b = 0; b < nb; ++b) {
      for (Eigen::Index i = block_start_[b]; i < block_start_[b + 1]; ++i) res[i] -= row_dot(i, d);
      scale(res, dn, b);
      for (Eigen::Index i = block_start_[b]; i < block_start_[b + 1]; ++i) x[i] += dn[i] = c_old * d[i] + c_res * dn[i];
    }
    std::swap(d, dn);
    rho = rho_next;
  }
  if (final_residual) {
    const Eigen::Index n = z.size();
#pragma omp parallel for schedule(static) if (parallel_)
    for (Eigen::Index i = 0; i < n; ++i) res[i] -= row_dot(i, d);
  }
}

// Nodal-block Gauss–Seidel sweeps on A z = r (the thesis' GS_l), forward or backward.
void PMultigridPreconditioner::gauss_seidel(const Eigen::VectorXd& r, Eigen::VectorXd& z, bool forward) const {
  const Eigen::Index nb = static_cast<Eigen::Index>(block_start_.size()) - 1;
  for (int sweep = 0; sweep < options_.gauss_seidel_sweeps; ++sweep)
    for (Eigen::Index k = 0; k < nb; ++k) {
      const Eigen::Index b = forward ? k : nb - 1 - k;
      for (Eigen::Index i = block_start_[b]; i < block_start_[b + 1]; ++i) res_[i] = r[i] - row_dot(i, z.data());
      scale(res_.data(), d_.data(), b);
      for (Eigen::Index i = block_start_[b]; i < block_start_[b + 1]; ++i) z[i] += d_[i];
    }
}

// Thesis Algorithm 3 with two levels, as a preconditioner (z = M^-1 r, z_0 = 0).
void PMultigridPreconditioner::apply(const Eigen::VectorXd& r, Eigen::VectorXd& z) const {
  const Eigen::Index n = r.size();
  if (z.size() != n) z.resize(n);
  z.setZero();
  const bool cheb = options_.smoother == PMultigridOptions::Smoother::Chebyshev;
  // Lines 3-4: pre-smoothing, then the residual.
  if (cheb) {
    res_ = r;
    chebyshev(z, true);
  } else {
    gauss_seidel(r, z, true);
    residual(r, z, res_);
  }
  if (coarse_size() > 0) {
    // Line 5: restriction r_c = P^T res, by P's columns in parallel.
    const SparseMatrix& P = transfer_.P;
    const Eigen::Index nc = P.cols();
#pragma omp parallel for schedule(static) if (parallel_)
    for (Eigen::Index l = 0; l < nc; ++l) {
      double s = 0.0;
      for (SparseMatrix::InnerIterator it(P, l); it; ++it) s += it.value() * res_[it.row()];
      rc_[l] = s;
    }
    coarse_->solve(rc_, xc_);  // line 7
    // Line 9: prolongation z += P x_c, by P's rows in parallel.
    const RowSparseMatrix& R = transfer_.P_rows;
#pragma omp parallel for schedule(static) if (parallel_)
    for (Eigen::Index i = 0; i < n; ++i) {
      double s = 0.0;
      for (RowSparseMatrix::InnerIterator it(R, i); it; ++it) s += it.value() * xc_[it.col()];
      z[i] += s;
    }
  }
  // Line 10: post-smoothing, the adjoint of the pre-smoother.
  if (cheb) {
    residual(r, z, res_);
    chebyshev(z, false);
  } else {
    gauss_seidel(r, z, false);
  }
}

std::unique_ptr<Preconditioner> make_p_multigrid_preconditioner() { return make_p_multigrid_preconditioner({}); }

std::unique_ptr<Preconditioner> make_p_multigrid_preconditioner(const PMultigridOptions& options) {
  return std::make_unique<PMultigridPreconditioner>(options);
}

}  // namespace hofem
