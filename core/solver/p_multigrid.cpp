#include "solver/p_multigrid.hpp"

#include "linalg/boomeramg.hpp"

#include "linalg/chebyshev_recurrence.hpp"
#include "linalg/cholmod_solver.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

// Defaults (PMultigridOptions): see the measurements in DEVELOPERS.md's solver
// section and benchmarks/bench_time_to_error.cpp.

namespace hofem {

PMultigridPreconditioner::PMultigridPreconditioner(PMultigridOptions options) : options_(std::move(options)) {
  if (options_.chebyshev_degree < 1 || !(options_.smoothing_range > 1.0) || !(options_.eigenvalue_safety >= 1.0) ||
      options_.eigenvalue_iterations < 1 || options_.direct_coarse_limit < 0)
    throw std::invalid_argument(
        "pmg: needs chebyshev_degree >= 1, smoothing_range > 1, eigenvalue_safety >= 1, eigenvalue_iterations >= 1, "
        "direct_coarse_limit >= 0");
}

PMultigridPreconditioner::~PMultigridPreconditioner() = default;

int PMultigridPreconditioner::coarse_analyses() const { return coarse_direct_ ? coarse_direct_->analyses() : 0; }

bool PMultigridPreconditioner::setup(const SparseMatrix& A) { return check(A) && prepare(A, nullptr); }

bool PMultigridPreconditioner::setup(const SparseMatrix& A, const BlockSparseMatrix<double>& blocks) {
  return check(A) && prepare(A, &blocks);
}

bool PMultigridPreconditioner::check(const SparseMatrix& A) {
  if (!mesh_view_.valid()) return fail("pmg: needs the mesh and DOF map (set_mesh_view) before setup");
  const Mesh& mesh = *mesh_view_.mesh;
  if (mesh.order < 2)
    return fail(fmt::format(
        "pmg needs element order >= 2 (the mesh is order {}, there is no coarser p level; use amg or ic0)",
        mesh.order));
  if (A.rows() != mesh_view_.dofs->num_free() || A.cols() != A.rows() || !A.isCompressed())
    return fail(fmt::format("pmg: matrix is {}x{} (compressed: {}), the DOF map has {} free DOFs", A.rows(), A.cols(),
                            A.isCompressed(), mesh_view_.dofs->num_free()));
  return true;
}

// Hierarchy once per mesh view (mesh and DOF map), block structures and Galerkin patterns once
// per fine pattern, values (and the smoothers' scaling and eigenvalue bounds) every
// time.
bool PMultigridPreconditioner::prepare(const SparseMatrix& A, const BlockSparseMatrix<double>* blocks) {
  const DofMap& dofs = *mesh_view_.dofs;
  const Mesh& mesh = *mesh_view_.mesh;
  const std::array<std::int64_t, 4> shape{static_cast<std::int64_t>(mesh.cell), mesh.order, mesh.num_nodes(),
                                          mesh.num_elements()};
  if (dofs.identity() == 0 || dofs.identity() != dofs_identity_ || shape != mesh_shape_) {
    std::vector<int> orders{mesh.order};
    if (options_.coarsening == PMultigridOptions::Coarsening::ByOne && mesh.cell == CellType::Tetrahedron)
      for (int q = mesh.order - 1; q >= 1; --q) orders.push_back(q);
    else
      orders.push_back(1);
    try {
      hierarchy_ = std::make_unique<PHierarchy>(mesh, dofs, orders);
    } catch (const std::invalid_argument& e) {
      return fail(std::string("pmg: ") + e.what());
    }
    dofs_identity_ = dofs.identity();
    mesh_shape_ = shape;
    pattern_hash_ = 0;
    levels_.clear();
    levels_.resize(static_cast<size_t>(hierarchy_->num_levels() - 1));
    if (!levels_.empty() && mesh_view_.block_elements && !mesh_view_.block_elements->empty()) {
      AdditiveSchwarzOptions o;
      o.nodal_uncovered = true;
      levels_[0].blocks = std::make_unique<AdditiveSchwarzPreconditioner>(o);
      levels_[0].blocks->set_mesh_view(mesh_view_);
    }
  }
  if (!levels_.empty() && levels_[0].blocks && !levels_[0].blocks->setup(A))
    return fail("pmg: fine-level smoother: " + levels_[0].blocks->last_error());
  // The fine level's operator: the caller's block copy, or a copy of our own.
  fine_blocks_ = blocks;
  // The caller's block copy carries A's fingerprint when its builder hashed A already.
  const std::uint64_t hash = blocks && blocks->source_fingerprint() != 0 ? blocks->source_fingerprint() : pattern_fingerprint(A);
  if (hash != pattern_hash_) {
    levels_[0].exact = blocks ? BlockSparseMatrix<double>() : BlockSparseMatrix<double>(A);
    for (size_t l = 0; l < levels_.size(); ++l)
      coarser_operator(l) = galerkin_structure(level_operator(l), hierarchy_->transfer(static_cast<int>(l)));
    pattern_hash_ = hash;
  } else if (!blocks) {
    if (levels_[0].exact.rows() != A.rows()) levels_[0].exact = BlockSparseMatrix<double>(A);  // had the caller's
    else levels_[0].exact.set_values(A);
  }
  for (size_t l = 0; l < levels_.size(); ++l) {
    if (!set_level_values(levels_[l], l)) return false;
    galerkin_values(level_operator(l), hierarchy_->transfer(static_cast<int>(l)), coarser_operator(l));
  }

  // The order-1 level: factorised when small, one AMG V-cycle when large.
  if (coarse_.rows() == 0) return true;  // every vertex constrained: smoothing only
  direct_coarse_ = coarse_.rows() <= options_.direct_coarse_limit;
  const SparseMatrix Ac = coarse_.to_sparse();
  if (direct_coarse_) {
    if (!coarse_direct_) coarse_direct_ = std::make_unique<CholmodSolver>(/*serial_solves=*/true);
    if (!coarse_direct_->factorize(Ac))  // CHOLMOD re-analyses by itself on a new pattern
      return fail("pmg: the order-1 operator P^T A P is not positive definite (A is not SPD)");
  } else {
    if (!coarse_amg_)
      coarse_amg_ = std::make_unique<BoomerAmgPreconditioner>(options_.coarse_amg, boomeramg_options(options_.coarse_amg));
    if (!coarse_amg_->setup(Ac)) return fail("pmg: order-1 level: " + coarse_amg_->last_error());
  }
  return true;
}

// Single-precision copy, D_b^-1 for every node (from the diagonal blocks, SPD when
// A is), the Chebyshev bound, work vectors.
bool PMultigridPreconditioner::set_level_values(Level& level, std::size_t index) {
  level.smooth.assign(level_operator(index));
  const Eigen::Index nb = level.smooth.block_rows();
  level.inverse_diagonal.resize(static_cast<size_t>(nb));
  Eigen::Index failed = nb;  // the first node whose block is not SPD (the same whatever the thread count)
#pragma omp parallel for schedule(static) reduction(min : failed) if (level.smooth.parallel())
  for (Eigen::Index b = 0; b < nb; ++b) {
    const Eigen::LLT<Eigen::Matrix3d> llt(level.smooth.diagonal_block(b));
    if (llt.info() != Eigen::Success) failed = std::min(failed, b);
    else level.inverse_diagonal[b] = llt.solve(Eigen::Matrix3d::Identity());
  }
  if (failed < nb)
    return fail(fmt::format("pmg: level {} (order {}): diagonal block of node {} is not positive definite", index,
                            hierarchy_->level(static_cast<int>(index)).order, failed));
  const Eigen::Index n = level.smooth.rows();
  level.res.setZero(n);
  level.d.setZero(n);
  level.d_next.setZero(n);
  if (level.blocks) level.w.setZero(n);
  estimate_lambda_max(level);
  return true;
}

// Lanczos estimate of lambda_max(D^-1 A) from the CG coefficients (the Lanczos
// tridiagonal T: T_jj = 1/alpha_j + beta_{j-1}/alpha_{j-1}, T_{j,j+1} = sqrt(beta_j)/alpha_j),
// as deal.II's PreconditionChebyshev does. Ritz values approach lambda_max from
// below, hence the safety factor. Start: a fixed pseudo-random vector, so set-ups
// are reproducible and no smooth mode is missed.
void PMultigridPreconditioner::estimate_lambda_max(Level& level) const {
  const BlockSparseMatrix<float>& A = level.smooth;
  const Eigen::Index n = A.rows();
  Eigen::VectorXd r(n), z(n), p, q(n);
  std::uint64_t s = 88172645463325252ull;
  for (Eigen::Index i = 0; i < n; ++i) {
    s ^= s << 13, s ^= s >> 7, s ^= s << 17;  // xorshift64
    r[i] = static_cast<double>(s >> 11) * 0x1.0p-53 - 0.5;
  }
  auto scale = [&](const Eigen::VectorXd& in, Eigen::VectorXd& out) { smoother_inverse(level, in, out); };
  scale(r, z);
  p = z;
  double rz = r.dot(z), alpha_prev = 1.0, beta_prev = 0.0;
  const int m = options_.eigenvalue_iterations;
  Eigen::VectorXd diag = Eigen::VectorXd::Zero(m), off = Eigen::VectorXd::Zero(m);
  int k = 0;
  for (; k < m; ++k) {
    A.multiply(p, q);
    const double pAp = p.dot(q);
    if (!(pAp > 0.0) || !(rz > 0.0)) break;
    const double alpha = rz / pAp;
    r.noalias() -= alpha * q;
    scale(r, z);
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
  level.lambda_max = options_.eigenvalue_safety * est;
}

void PMultigridPreconditioner::smoother_inverse(const Level& level, const Eigen::VectorXd& r, Eigen::VectorXd& z) const {
  if (level.blocks) {
    level.blocks->apply(r, z);
    return;
  }
  const Eigen::Index nb = level.smooth.block_rows();
  z.resize(r.size());
#pragma omp parallel for schedule(static) if (level.smooth.parallel())
  for (Eigen::Index b = 0; b < nb; ++b) z.segment<3>(3 * b) = level.inverse_diagonal[b] * r.segment<3>(3 * b);
}

// chebyshev() below with S (the cut cells' Schwarz blocks and nodal blocks) for
// D^-1: the same recurrence, each step a product, a pass of S and the updates.
void PMultigridPreconditioner::chebyshev_blocks(const Level& level, Eigen::VectorXd& z, bool final_residual) const {
  const BlockSparseMatrix<float>& A = level.smooth;
  ChebyshevRecurrence cheb(level.lambda_max / options_.smoothing_range, level.lambda_max);
  smoother_inverse(level, level.res, level.w);
  level.d = level.w / cheb.theta();
  z += level.d;
  for (int k = 1; k < options_.chebyshev_degree; ++k) {
    const ChebyshevRecurrence::Step c = cheb.next();
    A.multiply(level.d, level.w);
    level.res -= level.w;
    smoother_inverse(level, level.res, level.w);
    level.d_next = c.c_old * level.d + c.c_res * level.w;
    z += level.d_next;
    level.d.swap(level.d_next);
  }
  if (final_residual) {
    A.multiply(level.d, level.w);
    level.res -= level.w;
  }
}

// Chebyshev smoothing (Saad, Iterative Methods, Alg. 12.1, with D^-1): on entry
// level.res = b - A z; z gains a degree-k polynomial in D^-1 A applied to D^-1 res.
// With final_residual, res is left as the residual of the new z. Each step is one
// pass over the block rows: res -= A d on a row, then that row's new direction.
void PMultigridPreconditioner::chebyshev(const Level& level, Eigen::VectorXd& z, bool final_residual) const {
  if (level.blocks) {
    chebyshev_blocks(level, z, final_residual);
    return;
  }
  const BlockSparseMatrix<float>& A = level.smooth;
  ChebyshevRecurrence cheb(level.lambda_max / options_.smoothing_range, level.lambda_max);
  const double theta = cheb.theta();
  const Eigen::Index nb = A.block_rows();
  double* d = level.d.data();
  double* dn = level.d_next.data();
  double* res = level.res.data();
  double* x = z.data();
  const Eigen::Matrix3d* Di = level.inverse_diagonal.data();
#pragma omp parallel for schedule(static) if (A.parallel())
  for (Eigen::Index b = 0; b < nb; ++b) {
    const Eigen::Vector3d step = Di[b] * Eigen::Map<const Eigen::Vector3d>(res + 3 * b) / theta;
    Eigen::Map<Eigen::Vector3d>(d + 3 * b) = step;
    Eigen::Map<Eigen::Vector3d>(x + 3 * b) += step;
  }
  for (int k = 1; k < options_.chebyshev_degree; ++k) {
    const ChebyshevRecurrence::Step c = cheb.next();
    const double c_old = c.c_old, c_res = c.c_res;
#pragma omp parallel for schedule(static) if (A.parallel())
    for (Eigen::Index b = 0; b < nb; ++b) {
      Eigen::Map<Eigen::Vector3d> rb(res + 3 * b);
      rb -= A.row_product(b, d);
      const Eigen::Vector3d step = c_old * Eigen::Map<const Eigen::Vector3d>(d + 3 * b) + c_res * (Di[b] * rb);
      Eigen::Map<Eigen::Vector3d>(dn + 3 * b) = step;
      Eigen::Map<Eigen::Vector3d>(x + 3 * b) += step;
    }
    std::swap(d, dn);
  }
  if (final_residual) {
#pragma omp parallel for schedule(static) if (A.parallel())
    for (Eigen::Index b = 0; b < nb; ++b) Eigen::Map<Eigen::Vector3d>(res + 3 * b) -= A.row_product(b, d);
  }
}

// Thesis Algorithm 3 on level l: x = V-cycle(b), from x = 0.
void PMultigridPreconditioner::vcycle(std::size_t l, const Eigen::VectorXd& b, Eigen::VectorXd& x) const {
  if (l == levels_.size()) {  // the order-1 level
    if (coarse_.rows() == 0) return;
    if (direct_coarse_)
      coarse_direct_->solve(b, x);
    else
      coarse_amg_->apply(b, x);
    return;
  }
  const Level& level = levels_[l];
  const NodeTransfer& t = hierarchy_->transfer(static_cast<int>(l));
  x.setZero(b.size());
  level.res = b;
  chebyshev(level, x, true);                      // lines 3-4: pre-smoothing, residual
  apply_nodal(t.R, level.res, level.b_coarse);    // line 5: restriction
  vcycle(l + 1, level.b_coarse, level.x_coarse);  // line 7: the coarser levels
  apply_nodal(t.P, level.x_coarse, level.d);      // line 9: prolongation (into d, free here)
  x += level.d;
  level.smooth.residual(b, x, level.res);         // line 10: post-smoothing on the new residual
  chebyshev(level, x, false);
}

void PMultigridPreconditioner::apply(const Eigen::VectorXd& r, Eigen::VectorXd& z) const { vcycle(0, r, z); }

// Per smoothed level with n unknowns (k = Chebyshev degree): the vcycle above
// makes 2k passes over the single-precision matrix (pre-smoothing: k - 1 fused
// steps and the final residual; post-smoothing: the residual and k - 1 steps),
// each A.bytes() plus its operand x (8n); every pass also streams the vectors
// of a fused step (res read and written 16n, D^-1 72 bytes per node = 24n, the
// new direction 8n, z read and written 16n: 64n), and the two passes without a
// product (each smoothing's first step) the same 64n. Transfers: R and P once
// each (16 bytes per stored weight, 64-bit index and value, plus their 3-vector
// operands and results). The order-1 level: one pass over its matrix in
// compressed columns (16 bytes per nonzero), a lower bound for BoomerAMG's
// V-cycle and CHOLMOD's two triangular solves alike.
double PMultigridPreconditioner::bytes_per_apply() const {
  const double k = options_.chebyshev_degree;
  double bytes = 0.0;
  for (size_t l = 0; l < levels_.size(); ++l) {
    const Level& level = levels_[l];
    const double n = static_cast<double>(level.smooth.rows());
    bytes += 2.0 * k * (static_cast<double>(level.smooth.bytes()) + 8.0 * n) + (2.0 * k + 2.0) * 64.0 * n;
    const NodeTransfer& t = hierarchy_->transfer(static_cast<int>(l));
    const double weights = static_cast<double>(t.P.nonZeros() + t.R.nonZeros());
    bytes += 16.0 * weights + 2.0 * 8.0 * (n + 3.0 * static_cast<double>(t.P.cols()));
  }
  bytes += 16.0 * 9.0 * static_cast<double>(coarse_.blocks());
  return bytes;
}

}  // namespace hofem
