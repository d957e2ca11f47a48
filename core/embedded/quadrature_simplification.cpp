#include "embedded/quadrature_simplification.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/QR>
#include <Eigen/SVD>
#include <fmt/format.h>
#include <glpk.h>

#include <algorithm>
#include <numbers>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <type_traits>
#include <vector>

namespace hofem {

int polynomial_space_dimension(int degree) { return (degree + 1) * (degree + 2) * (degree + 3) / 6; }

namespace {

void validate(const Eigen::MatrixXd& points, const Eigen::VectorXd& weights, int degree) {
  if (degree < 0) throw std::invalid_argument(fmt::format("simplify_quadrature: degree must be >= 0, got {}", degree));
  if (points.rows() != 3)
    throw std::invalid_argument(fmt::format("simplify_quadrature: points must have 3 rows, got {}", points.rows()));
  if (points.cols() != weights.size())
    throw std::invalid_argument(fmt::format("simplify_quadrature: points has {} columns but weights has {} entries",
                                            points.cols(), weights.size()));
  if (!points.allFinite()) throw std::invalid_argument("simplify_quadrature: points contain a NaN or infinity");
  for (Eigen::Index j = 0; j < weights.size(); ++j)
    if (!std::isfinite(weights[j]) || weights[j] < 0.0)
      throw std::invalid_argument(
          fmt::format("simplify_quadrature: weights must be finite and >= 0, weights[{}] = {}", j, weights[j]));
}

// P (M x N) of Longva et al. 2020 eq. 7 in the basis of eq. 9: T_a(x) T_b(y) T_c(z), a + b + c <= m,
// each coordinate mapped from the points' bounding box onto [-1, 1] (§4.4.3: a
// small cluster of points would otherwise see nearly dependent polynomials). The
// map t = 2 (x - lo) / (hi - lo) - 1 stays in [-1, 1] in floating point (rounding
// is monotone), so no clamping perturbs the polynomials; x - lo and hi - lo are
// exact for clusters (Sterbenz). An axis whose extent is at rounding level of its
// coordinates is flat: t = 0 there, and the polynomials that vary along it repeat
// others (the rank drops instead of filling with rounding noise).
Eigen::MatrixXd chebyshev_matrix(const Eigen::MatrixXd& points, int m) {
  const Eigen::Index n = points.cols();
  const Eigen::Vector3d lo = points.rowwise().minCoeff(), hi = points.rowwise().maxCoeff();
  const Eigen::Vector3d extent = hi - lo;
  std::array<bool, 3> flat{};
  for (int d = 0; d < 3; ++d)
    flat[d] = !(extent[d] > 16.0 * std::numeric_limits<double>::epsilon() * std::max(std::abs(lo[d]), std::abs(hi[d])));
  Eigen::MatrixXd P(polynomial_space_dimension(m), n);
  Eigen::MatrixXd T(3, m + 1);  // T(d, a) = T_a(mapped coordinate d)
  for (Eigen::Index j = 0; j < n; ++j) {
    for (int d = 0; d < 3; ++d) {
      const double x = flat[d] ? 0.0 : 2.0 * ((points(d, j) - lo[d]) / extent[d]) - 1.0;
      T(d, 0) = 1.0;
      if (m >= 1) T(d, 1) = x;
      for (int a = 2; a <= m; ++a) T(d, a) = 2.0 * x * T(d, a - 1) - T(d, a - 2);
    }
    int k = 0;
    double* column = &P(0, j);
    for (int a = 0; a <= m; ++a)
      for (int b = 0; a + b <= m; ++b) {
        const double ab = T(0, a) * T(1, b);  // the same products, in the same order, as T_a T_b T_c
        for (int c = 0; a + b + c <= m; ++c) column[k++] = ab * T(2, c);
      }
  }
  return P;
}

// V_r (N x r) of P = U S V^T. P is short and wide: a Householder QR of P^T = Q R
// (O(N M^2), backward stable) reduces it to the M x M factor R, whose Jacobi SVD
// R = X S Y^T is accurate to rounding; then P^T = (Q X) S Y^T, so V = Q X.
Eigen::MatrixXd right_singular_vectors(const Eigen::MatrixXd& P, double rank_tolerance, int& rank) {
  const Eigen::Index m = P.rows(), n = P.cols();
  const Eigen::HouseholderQR<Eigen::MatrixXd> qr(P.transpose());
  const Eigen::MatrixXd R = qr.matrixQR().topRows(m).triangularView<Eigen::Upper>();
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(R, Eigen::ComputeFullU);
  const Eigen::VectorXd& s = svd.singularValues();
  rank = 0;
  while (rank < m && s[rank] > rank_tolerance * s[0]) ++rank;
  Eigen::MatrixXd V = Eigen::MatrixXd::Zero(n, rank);
  V.topRows(m) = svd.matrixU().leftCols(rank);
  return qr.householderQ() * V;
}

// Longva et al. 2020 eq. 10 by GLPK's simplex with a zero objective: any basic feasible point
// has at most r non-zeros. Returns the basic columns and their values (a basic
// value may be 0 or, within GLPK's tolerance, slightly negative), or nothing
// (with `error` set) when GLPK does not succeed.
struct BasicSolution {
  std::vector<int> columns;
  Eigen::VectorXd values;
};

std::optional<BasicSolution> basic_feasible_point(const Eigen::MatrixXd& A, const Eigen::VectorXd& b,
                                                  std::string& error) {
  const int r = static_cast<int>(A.rows()), n = static_cast<int>(A.cols());
  const bool own_env = glp_init_env() == 0;  // 1: this thread already had an environment
  const int old_term = glp_term_out(GLP_OFF);
  glp_prob* lp = glp_create_prob();
  glp_set_obj_dir(lp, GLP_MIN);
  glp_add_rows(lp, r);
  glp_add_cols(lp, n);
  for (int i = 0; i < r; ++i) glp_set_row_bnds(lp, i + 1, GLP_FX, b[i], b[i]);
  std::vector<int> ind(r + 1);
  std::vector<double> val(r + 1);
  for (int j = 0; j < n; ++j) {
    glp_set_col_bnds(lp, j + 1, GLP_LO, 0.0, 0.0);
    int len = 0;
    for (int i = 0; i < r; ++i)
      if (A(i, j) != 0.0) {
        ++len;
        ind[len] = i + 1;
        val[len] = A(i, j);
      }
    glp_set_mat_col(lp, j + 1, len, ind.data(), val.data());
  }
  // No glp_scale_prob: the rows of V_r^T are orthonormal already, and GLPK's
  // iterative scaling of this dense matrix costs more than the simplex itself.
  glp_adv_basis(lp, 0);
  glp_smcp parm;
  glp_init_smcp(&parm);
  parm.msg_lev = GLP_MSG_OFF;
  parm.presolve = GLP_OFF;  // the solution we read is then GLPK's own basic point
  // With a zero objective every basis is dual feasible, so the dual simplex goes
  // straight at the primal infeasibilities (2-3x faster than the primal here at
  // m = 8..10); GLP_DUALP falls back to the primal simplex if the dual fails.
  parm.meth = GLP_DUALP;
  const int ret = glp_simplex(lp, &parm);
  const int status = glp_get_status(lp);
  std::optional<BasicSolution> out;
  if (ret != 0) {
    error = fmt::format("GLPK glp_simplex returned error code {}", ret);
  } else if (status != GLP_OPT && status != GLP_FEAS) {
    error = fmt::format("GLPK found no feasible point (status {})", status);
  } else {
    BasicSolution s;
    std::vector<double> v;
    for (int j = 0; j < n; ++j)
      if (glp_get_col_stat(lp, j + 1) == GLP_BS) {
        s.columns.push_back(j);
        v.push_back(glp_get_col_prim(lp, j + 1));
      }
    s.values = Eigen::Map<const Eigen::VectorXd>(v.data(), static_cast<Eigen::Index>(v.size()));
    out = std::move(s);
  }
  glp_delete_prob(lp);
  glp_term_out(old_term);
  if (own_env) glp_free_env();
  return out;
}

// Weights on `support` solving the constraints of eq. 10 restricted to those
// columns, A_S w_S = c, by least squares (column-pivoted QR): the active set's
// solve on its passive columns, and the refinement of the simplex's basic point.
// At most r columns of a basis matrix: the system is square or overdetermined and
// consistent up to rounding and dropped weights.
Eigen::VectorXd solve_on(const Eigen::MatrixXd& A, const Eigen::VectorXd& c, const std::vector<int>& support) {
  if (support.empty()) return {};
  const Eigen::MatrixXd AS = A(Eigen::all, support);
  return AS.colPivHouseholderQr().solve(c);
}


// The fast path to the same active-set answer (SimplificationOptions::fast).
//
// Lawson & Hanson's method depends on the constraints A w = c only through the
// gradient A^T (c - A w) and the least-squares solutions on the passive columns,
// and both are unchanged when A and c are multiplied by an orthogonal matrix O:
// (O A)^T (O c - O A w) = A^T (c - A w), |O A_P z - O c| = |A_P z - c|. Any
// orthonormal basis of the row space of P therefore gives the same iterates as
// V_r^T of the SVD, in exact arithmetic. The SVD path spends ~60 % of a cut
// Hex20 cell's simplification (measured: N ~ 2,000 points, M = 84: QR of P^T
// 5.6 ms, Jacobi SVD 3.5 ms, forming Q V 11.8 ms of 33.5 ms per cell); CholeskyQR2
// (Yamamoto, Nakatsukasa, Yanagisawa & Fukaya 2015, "Roundoff error analysis of
// the CholeskyQR2 algorithm", Electron. Trans. Numer. Anal. 44) builds an
// orthonormal basis from two Gram matrices and triangular solves (matrix-matrix
// products), orthonormal to rounding when kappa(P)^2 u is well below 1 (their
// analysis; kappa <= 1e7 gives ~1e-2). We take it only when kappa(P) <=
// kMaxFastCondition, so that P also has full rank M on the SVD path (a rank
// tolerance below 1e-7 keeps every singular value); otherwise the SVD path runs.
// Measured on the 1,152 cut cells of the Hex20 cylinder on a 12 x 12 x 18 grid
// (kappa(P) from 1e2 to 8e5): the same points, bit for bit and in the same order,
// in every cell for both the stiffness LP and the stabilisation fold; weights
// equal to the last least-squares solve's conditioning (<= 4e-10 relative), moments
// to rounding; one thread, machine shared with a build: stiffness LP 46 -> 26 ms
// per cell, fold 30 -> 5 ms (the updated QR below does most of the fold's part).
constexpr double kMaxFastCondition = 1e7;

// Rows orthonormal, spanning the rows of P (M x N, full rank); false when P is
// too ill-conditioned for the fast path (then nothing is written).
bool orthonormal_rows(const Eigen::MatrixXd& P, Eigen::MatrixXd& A) {
  Eigen::MatrixXd G = Eigen::MatrixXd::Zero(P.rows(), P.rows());
  G.selfadjointView<Eigen::Lower>().rankUpdate(P);  // P P^T
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(G, Eigen::EigenvaluesOnly);
  const Eigen::VectorXd& lambda = eig.eigenvalues();  // ascending
  if (!(lambda[0] > 0.0) || !(lambda[lambda.size() - 1] <= kMaxFastCondition * kMaxFastCondition * lambda[0]))
    return false;
  for (int pass = 0; pass < 2; ++pass) {
    if (pass == 1) {
      G.setZero();
      G.selfadjointView<Eigen::Lower>().rankUpdate(A);
      // The first pass's rows are orthonormal to delta = |G - I|; for delta well
      // below 1 they are well conditioned, and the second pass makes them
      // orthonormal to rounding (the mechanism of the CholeskyQR2 analysis).
      const Eigen::MatrixXd I = Eigen::MatrixXd::Identity(G.rows(), G.cols());
      if (!((G.triangularView<Eigen::Lower>().toDenseMatrix() - I.triangularView<Eigen::Lower>().toDenseMatrix())
                .cwiseAbs()
                .maxCoeff() <= 0.1))
        return false;
    }
    const Eigen::LLT<Eigen::MatrixXd> llt(G.selfadjointView<Eigen::Lower>());
    if (llt.info() != Eigen::Success) return false;
    // Triangular solves, not products with the factor's inverse: a backward-stable
    // solve keeps L A = P to rounding, so the rows span those of P (the moments
    // the active set matches are P's). The explicit inverse was faster but lost a
    // factor kappa(P) there: moment residuals up to 4.7e-12 instead of 6.5e-16
    // on the default Hex20 cylinder's cut cells (measured).
    if (pass == 0) A = P;
    llt.matrixL().solveInPlace(A);  // first pass: rows orthonormal to ~kappa^2 eps; second: to rounding
  }
  return true;
}

// A_P = Q [R; 0] for the passive columns P of A (M x k, k <= M), updated when a
// column is appended or removed instead of factorised afresh (Golub & Van Loan,
// "Matrix Computations", 4th ed., §6.5.2: appending by one Householder
// reflection, removing by Givens rotations of the Hessenberg rest). d = Q^T c
// follows the same transformations, so z = R^-1 d[0, k) solves min |A_P z - c|.
class UpdatedQR {
 public:
  UpdatedQR(Eigen::Index m, const Eigen::VectorXd& c) : Q_(Eigen::MatrixXd::Identity(m, m)), R_(m, m), d_(c) {}
  Eigen::Index size() const { return k_; }
  // False when the column depends (to rounding) on the present ones; the active
  // set then leaves the decision to the reference path.
  bool append(const Eigen::VectorXd& a) {
    const Eigen::Index m = Q_.rows();
    if (k_ >= m) return false;
    Eigen::VectorXd u = Q_.transpose() * a;
    Eigen::VectorXd tail = u.tail(m - k_);
    double tau = 0.0, beta = 0.0;
    Eigen::VectorXd essential(m - k_ - 1);
    tail.makeHouseholder(essential, tau, beta);
    if (!(std::abs(beta) > 64.0 * std::numeric_limits<double>::epsilon() * a.norm())) return false;
    Eigen::VectorXd work(m);
    Q_.rightCols(m - k_).applyHouseholderOnTheRight(essential, tau, work.data());
    d_.tail(m - k_).applyHouseholderOnTheLeft(essential, tau, work.data());
    R_.col(k_).head(k_) = u.head(k_);
    R_(k_, k_) = beta;
    ++k_;
    return true;
  }
  void remove(Eigen::Index i) {
    for (Eigen::Index j = i; j + 1 < k_; ++j) R_.col(j).head(j + 2) = R_.col(j + 1).head(j + 2);
    --k_;
    for (Eigen::Index j = i; j < k_; ++j) {  // R(j + 1, j) is the subdiagonal left by the shift
      Eigen::JacobiRotation<double> G;
      G.makeGivens(R_(j, j), R_(j + 1, j));
      R_.block(j, j, 2, k_ - j).applyOnTheLeft(0, 1, G.adjoint());
      R_(j + 1, j) = 0.0;
      Q_.applyOnTheRight(j, j + 1, G);
      d_.applyOnTheLeft(j, j + 1, G.adjoint());
    }
  }
  Eigen::VectorXd solve() const {
    return R_.topLeftCorner(k_, k_).triangularView<Eigen::Upper>().solve(d_.head(k_));
  }

 private:
  Eigen::MatrixXd Q_, R_;
  Eigen::VectorXd d_;
  Eigen::Index k_ = 0;
};

// The least squares on the passive columns P, min |A_P z - c|, as the active
// set below asks for it: a column appended, columns removed (by position in P),
// a solve. The reference solves afresh each time (solve_on); the fast path
// updates a QR factorisation (UpdatedQR). append() is false when the column is
// dependent on the passive ones to rounding (the fast path then hands the cell
// to the reference).
class FreshLeastSquares {
 public:
  FreshLeastSquares(const Eigen::MatrixXd& A, const Eigen::VectorXd& c) : A_(A), c_(c) {}
  bool append(Eigen::Index j) {
    P_.push_back(static_cast<int>(j));
    return true;
  }
  void remove(Eigen::Index k) { P_.erase(P_.begin() + k); }
  Eigen::VectorXd solve() const { return solve_on(A_, c_, P_); }

 private:
  const Eigen::MatrixXd& A_;
  const Eigen::VectorXd& c_;
  std::vector<int> P_;
};

class UpdatedLeastSquares {
 public:
  UpdatedLeastSquares(const Eigen::MatrixXd& A, const Eigen::VectorXd& c) : A_(A), qr_(A.rows(), c) {}
  bool append(Eigen::Index j) { return qr_.append(A_.col(j)); }
  void remove(Eigen::Index k) { qr_.remove(k); }
  Eigen::VectorXd solve() const { return qr_.solve(); }

 private:
  const Eigen::MatrixXd& A_;
  UpdatedQR qr_;
};

// Lawson & Hanson (1974), "Solving Least Squares Problems", ch. 23: the active-set
// method for min |A w - c| over w >= 0. Its passive (positive) columns stay
// linearly independent, so it ends with at most rank(A) = r positive weights: when
// c lies in the cone of A's columns (it does: w0 >= 0 is a solution), a basic
// feasible point of eq. 10, the same kind of answer as the simplex's. `ls` solves
// on the passive columns (FreshLeastSquares or UpdatedLeastSquares: the same
// steps and decisions); `dependent` is set when it refused a column. The fast
// path's final weights come from a fresh solve on the passive set.
struct ActiveSetResult {
  std::vector<int> support;
  Eigen::VectorXd weights;
  bool converged = false;
};

template <class LeastSquares>
ActiveSetResult active_set_nnls(const Eigen::MatrixXd& A, const Eigen::VectorXd& c, int max_iterations,
                                LeastSquares& ls, bool& dependent) {
  const Eigen::Index n = A.cols();
  std::vector<char> passive(static_cast<size_t>(n), 0);
  std::vector<int> P;
  Eigen::VectorXd w = Eigen::VectorXd::Zero(n), r = c, z;
  // A's rows are orthonormal (|A^T r| <= |r|): a gradient below this is rounding
  // of a residual at the level of eps |c| per column summed over the N columns.
  const double tolerance = 16.0 * std::numeric_limits<double>::epsilon() * c.norm() * std::sqrt(static_cast<double>(n));
  ActiveSetResult out;
  dependent = false;
  for (int iteration = 0; iteration < max_iterations; ++iteration) {
    const Eigen::VectorXd g = A.transpose() * r;  // the negative gradient of |A w - c|^2 / 2
    Eigen::Index best = -1;
    double largest = tolerance;
    for (Eigen::Index j = 0; j < n; ++j)
      if (!passive[static_cast<size_t>(j)] && g[j] > largest) {
        largest = g[j];
        best = j;
      }
    if (best < 0) {
      out.converged = true;
      break;
    }
    if (!ls.append(best)) {
      dependent = true;
      return out;
    }
    passive[static_cast<size_t>(best)] = 1;
    P.push_back(static_cast<int>(best));
    // Inner loop: step from w towards the unconstrained solution z on P as far as
    // w stays >= 0, drop the columns that reach zero, and solve again.
    bool positive = false;
    for (size_t inner = 0; inner <= P.size() && !P.empty(); ++inner) {
      z = ls.solve();  // argmin |A_P z - c|
      if ((z.array() > 0.0).all()) {
        positive = true;
        break;
      }
      double alpha = 1.0;
      size_t blocking = 0;
      for (size_t k = 0; k < P.size(); ++k) {
        const double zk = z[static_cast<Eigen::Index>(k)];
        if (zk <= 0.0 && w[P[k]] / (w[P[k]] - zk) < alpha) {
          alpha = w[P[k]] / (w[P[k]] - zk);
          blocking = k;
        }
      }
      std::vector<int> kept;
      for (size_t k = 0; k < P.size(); ++k) {
        double& wk = w[P[k]];
        wk = k == blocking ? 0.0 : wk + alpha * (z[static_cast<Eigen::Index>(k)] - wk);
        if (wk > 0.0) {
          kept.push_back(P[k]);
        } else {
          wk = 0.0;
          passive[static_cast<size_t>(P[k])] = 0;
        }
      }
      // The dropped columns leave the least squares, last first (positions stay valid).
      for (size_t k = P.size(); k-- > 0;)
        if (w[P[k]] == 0.0) ls.remove(static_cast<Eigen::Index>(k));
      P = std::move(kept);
    }
    if (positive)
      for (size_t k = 0; k < P.size(); ++k) w[P[k]] = z[static_cast<Eigen::Index>(k)];
    r = c;
    for (const int j : P) r -= w[j] * A.col(j);
  }
  out.support = P;
  constexpr bool fresh = std::is_same_v<LeastSquares, FreshLeastSquares>;
  out.weights = !fresh && out.converged && !P.empty() ? solve_on(A, c, P) : Eigen::VectorXd(w(P));
  return out;
}

// B w as accurate_product, faster: sums of 16 terms in double (error <= 16 eps of
// their absolute sum), then in long double. The fast path's moments; the
// reference path keeps accurate_product.
Eigen::VectorXd chunked_product(const Eigen::MatrixXd& B, const Eigen::VectorXd& w) {
  constexpr Eigen::Index chunk = 16;
  std::vector<long double> sum(static_cast<size_t>(B.rows()), 0.0L);
  for (Eigen::Index j0 = 0; j0 < B.cols(); j0 += chunk) {
    const Eigen::Index n = std::min(chunk, B.cols() - j0);
    const Eigen::VectorXd part = B.middleCols(j0, n) * w.segment(j0, n);
    for (Eigen::Index i = 0; i < B.rows(); ++i) sum[static_cast<size_t>(i)] += part[i];
  }
  Eigen::VectorXd out(B.rows());
  for (Eigen::Index i = 0; i < B.rows(); ++i) out[i] = static_cast<double>(sum[static_cast<size_t>(i)]);
  return out;
}

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// B w summed in long double. The moments of the input rule are sums of N terms
// whose rounding in double (~sqrt(N) eps relative) would otherwise be the accuracy
// floor of the simplified rule and hide from its measured residual.
Eigen::VectorXd accurate_product(const Eigen::MatrixXd& B, const Eigen::VectorXd& w) {
  std::vector<long double> sum(static_cast<size_t>(B.rows()), 0.0L);
  for (Eigen::Index j = 0; j < B.cols(); ++j)
    for (Eigen::Index i = 0; i < B.rows(); ++i) sum[static_cast<size_t>(i)] += static_cast<long double>(B(i, j)) * w[j];
  Eigen::VectorXd out(B.rows());
  for (Eigen::Index i = 0; i < B.rows(); ++i) out[i] = static_cast<double>(sum[static_cast<size_t>(i)]);
  return out;
}

// max_k |(P_S w_S - P w0)_k| / sum |w0| (SimplifiedRule::moment_residual), in long double.
double moment_residual(const Eigen::MatrixXd& P, const Eigen::VectorXd& Pw0, double scale,
                       const std::vector<int>& support, const Eigen::VectorXd& w) {
  double worst = 0.0;
  for (Eigen::Index i = 0; i < P.rows(); ++i) {
    long double r = -static_cast<long double>(Pw0[i]);
    for (size_t k = 0; k < support.size(); ++k)
      r += static_cast<long double>(w[static_cast<Eigen::Index>(k)]) * P(i, support[k]);
    worst = std::max(worst, static_cast<double>(std::fabs(r)));
  }
  return worst / scale;
}

}  // namespace

SimplifiedRule simplify_quadrature(const Eigen::MatrixXd& points, const Eigen::VectorXd& weights, int degree,
                                   const SimplificationOptions& options) {
  validate(points, weights, degree);
  SimplifiedRule out;
  out.points = points;
  out.weights = weights;
  out.points_before = static_cast<int>(points.cols());
  out.basis_size = polynomial_space_dimension(degree);
  const double total = weights.sum();
  if (out.points_before <= out.basis_size) {
    out.message = fmt::format("N = {} <= M = {}: nothing to simplify", out.points_before, out.basis_size);
    return out;
  }
  if (total <= 0.0) {
    out.message = "all weights are zero: nothing to simplify";
    return out;
  }
  // Work with weights of mean 1, so that GLPK's absolute feasibility tolerances
  // (~1e-7) are relative to a typical weight, whatever the cell's size.
  const double unit = total / static_cast<double>(weights.size());
  const Eigen::VectorXd w0 = weights / unit;
  const Eigen::MatrixXd P = chebyshev_matrix(points, degree);
  const bool fast_rows = options.fast && options.method == SimplificationMethod::ActiveSet &&
                         options.rank_tolerance * kMaxFastCondition < 1.0;  // full rank on both paths
  const Eigen::VectorXd Pw0 = fast_rows ? chunked_product(P, w0) : accurate_product(P, w0);
  const double scale = w0.sum();
  // Orthonormal constraints: CholeskyQR2 on the fast path (full rank, see
  // orthonormal_rows), V_r^T of the SVD otherwise; the same active-set iterates.
  Eigen::MatrixXd A;
  bool fast = fast_rows && orthonormal_rows(P, A);
  if (fast) out.rank = static_cast<int>(P.rows());
  else A = right_singular_vectors(P, options.rank_tolerance, out.rank).transpose();
  Eigen::VectorXd c = fast ? chunked_product(A, w0) : accurate_product(A, w0);
  // The kept points and their weights (in units of `unit`) as the result.
  auto accept = [&](const std::vector<int>& support, const Eigen::VectorXd& w, double residual, const char* method,
                    const std::string& note) {
    const Eigen::Index n = static_cast<Eigen::Index>(support.size());
    out.points.resize(3, n);
    out.weights.resize(n);
    for (Eigen::Index k = 0; k < n; ++k) {
      out.points.col(k) = points.col(support[static_cast<size_t>(k)]);
      out.weights[k] = w[k] * unit;
    }
    out.moment_residual = residual;
    out.simplified = true;
    out.method = method;
    out.message = fmt::format("kept {} of {} points (rank {}, {}){}", n, out.points_before, out.rank, method, note);
    return out;
  };

  std::string fallback;  // why the active-set method's answer was not taken
  if (options.method == SimplificationMethod::ActiveSet) {
    const int iterations = options.active_set_iterations >= 0 ? options.active_set_iterations : 3 * out.rank + 50;
    ActiveSetResult nn;
    bool dependent = false;
    auto residual_of = [&](const ActiveSetResult& r) {
      const bool positive = !r.support.empty() && (r.weights.array() > 0.0).all();
      return positive ? moment_residual(P, Pw0, scale, r.support, r.weights) : kInfinity;
    };
    double residual = kInfinity;
    if (fast) {
      UpdatedLeastSquares ls(A, c);
      nn = active_set_nnls(A, c, iterations, ls, dependent);
      residual = residual_of(nn);
      // A passive column dependent to rounding (P has full rank, so rare), or an
      // answer the reference could have accepted differently: the reference path
      // from the start (its SVD rank and pivoted QR are made for such sets), so
      // that the simplex fallback below also sees the reference's constraints.
      if (dependent || !nn.converged || !(residual <= options.max_moment_residual)) {
        fast = false;
        A = right_singular_vectors(P, options.rank_tolerance, out.rank).transpose();
        c = accurate_product(A, w0);
      }
    }
    if (!fast) {
      FreshLeastSquares ls(A, c);
      nn = active_set_nnls(A, c, iterations, ls, dependent);
      residual = residual_of(nn);
    }
    if (nn.converged && residual <= options.max_moment_residual) {
      out.fast = fast;
      return accept(nn.support, nn.weights, residual, "active set", "");
    }
    fallback = nn.converged ? fmt::format("; active set missed the moments by {:.3e}, simplex used", residual)
                            : fmt::format("; active set stopped after {} iterations, simplex used", iterations);
  }

  std::string error;
  const std::optional<BasicSolution> basic = basic_feasible_point(A, c, error);
  if (!basic) {
    out.message = error + fallback + "; input rule returned unchanged";
    return out;
  }
  // GLPK's weights: the basic columns with a positive value.
  std::vector<int> glpk_support;
  std::vector<double> positive;
  for (size_t k = 0; k < basic->columns.size(); ++k)
    if (basic->values[static_cast<Eigen::Index>(k)] > 0.0) {
      glpk_support.push_back(basic->columns[k]);
      positive.push_back(basic->values[static_cast<Eigen::Index>(k)]);
    }
  const Eigen::VectorXd glpk_w = Eigen::Map<const Eigen::VectorXd>(positive.data(), std::ssize(positive));
  // Refined weights: solve on every basic column (a square, non-singular basis
  // matrix unless GLPK left fixed rows in the basis). Basic values that are zero
  // in exact arithmetic (degenerate vertices, e.g. symmetric point sets) come out
  // at rounding level with either sign: drop those <= 0 and solve again; each
  // drop moves the moments by about the dropped weight.
  std::vector<int> support = basic->columns;
  Eigen::VectorXd w = solve_on(A, c, support);
  for (int round = 0; round < 4 && !support.empty() && (w.array() <= 0.0).any(); ++round) {
    std::vector<int> kept;
    for (size_t k = 0; k < support.size(); ++k)
      if (w[static_cast<Eigen::Index>(k)] > 0.0) kept.push_back(support[k]);
    support = kept;
    w = solve_on(A, c, support);
  }
  const bool refined_ok = !support.empty() && (w.array() > 0.0).all();
  double residual = refined_ok ? moment_residual(P, Pw0, scale, support, w) : kInfinity;
  const double glpk_residual = glpk_support.empty() ? kInfinity : moment_residual(P, Pw0, scale, glpk_support, glpk_w);
  std::string note;
  if (glpk_residual < residual) {  // the refinement failed, or GLPK's point was already at rounding level
    support = glpk_support;
    w = glpk_w;
    residual = glpk_residual;
    if (!refined_ok) note = " (refinement gave weights <= 0: GLPK's weights kept)";
  }
  if (!(residual <= options.max_moment_residual)) {
    out.message = fmt::format("moment residual {:.3e} above the accepted {:.1e}{}; input rule returned unchanged",
                              residual, options.max_moment_residual, fallback);
    return out;
  }
  return accept(support, w, residual, "simplex", note + fallback);
}


namespace {

// Chebyshev values T_a(t), a <= m, of the three coordinates of t in [-1, 1]^3 (3 x (m + 1)).
void chebyshev_values(const double* t, int m, Eigen::Matrix<double, 3, Eigen::Dynamic>& T) {
  for (int d = 0; d < 3; ++d) {
    T(d, 0) = 1.0;
    if (m >= 1) T(d, 1) = t[d];
    for (int a = 2; a <= m; ++a) T(d, a) = 2.0 * t[d] * T(d, a - 1) - T(d, a - 2);
  }
}

// The fixed points of moment fitting for degree m: M = C(m+3, 3) approximate Fekete
// points of [-1, 1]^3 for the total-degree Chebyshev basis of chebyshev_matrix,
// chosen as Sommariva & Vianello 2009 ("Computing approximate Fekete points by QR
// factorizations of Vandermonde matrices", Comput. Math. Appl. 57, §2) do: the
// first M pivots of a column-pivoted QR of the Vandermonde matrix over a
// candidate grid, which keeps the square Vandermonde matrix of the chosen points
// well conditioned. Candidates: the tensor grid of (m + 4)^3 Chebyshev-Gauss
// nodes (interior, and unisolvent for degree m: more than m + 1 per axis).
struct FittingPoints {
  Eigen::MatrixXd points;                // 3 x M in [-1, 1]^3
  Eigen::FullPivLU<Eigen::MatrixXd> lu;  // of V(k, q) = p_k(points_q)
  double condition = 0.0;                // of V, for the record
};

Eigen::MatrixXd vandermonde(const Eigen::MatrixXd& t, int m) {
  Eigen::MatrixXd V(polynomial_space_dimension(m), t.cols());
  Eigen::Matrix<double, 3, Eigen::Dynamic> T(3, m + 1);
  for (Eigen::Index q = 0; q < t.cols(); ++q) {
    chebyshev_values(&t(0, q), m, T);
    int k = 0;
    for (int a = 0; a <= m; ++a)
      for (int b = 0; a + b <= m; ++b)
        for (int c = 0; a + b + c <= m; ++c) V(k++, q) = T(0, a) * T(1, b) * T(2, c);
  }
  return V;
}

std::unique_ptr<FittingPoints> make_fitting_points(int m) {
  const int n = m + 4, M = polynomial_space_dimension(m);
  Eigen::VectorXd nodes(n);
  for (int i = 0; i < n; ++i) nodes[i] = std::cos((2 * i + 1) * std::numbers::pi / (2 * n));
  Eigen::MatrixXd candidates(3, n * n * n);
  for (int i = 0, q = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k, ++q) candidates.col(q) << nodes[i], nodes[j], nodes[k];
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(vandermonde(candidates, m));
  auto out = std::make_unique<FittingPoints>();
  out->points.resize(3, M);
  for (int q = 0; q < M; ++q) out->points.col(q) = candidates.col(qr.colsPermutation().indices()[q]);
  const Eigen::MatrixXd V = vandermonde(out->points, m);
  out->lu.compute(V);
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(V);
  out->condition = svd.singularValues()[0] / svd.singularValues()[M - 1];
  return out;
}

const FittingPoints& fitting_points(int m) {
  static std::mutex mutex;
  static std::map<int, std::unique_ptr<FittingPoints>> cache;
  std::lock_guard<std::mutex> lock(mutex);
  auto& slot = cache[m];
  if (!slot) slot = make_fitting_points(m);
  return *slot;
}

}  // namespace

double fitting_condition(int degree) {
  if (degree < 0) throw std::invalid_argument(fmt::format("fitting_condition: degree must be >= 0, got {}", degree));
  return fitting_points(degree).condition;
}

constexpr int kMomentChunk = 16;

FittedRule fit_quadrature(const Eigen::MatrixXd& points, const Eigen::VectorXd& weights, int degree) {
  validate(points, weights, degree);
  FittedRule out;
  out.points = points;
  out.weights = weights;
  out.points_before = static_cast<int>(points.cols());
  const int M = polynomial_space_dimension(degree);
  if (out.points_before <= M) {
    out.message = fmt::format("N = {} <= M = {}: nothing to fit", out.points_before, M);
    return out;
  }
  const Eigen::Vector3d lo = points.rowwise().minCoeff(), hi = points.rowwise().maxCoeff(), extent = hi - lo;
  for (int d = 0; d < 3; ++d)
    if (!(extent[d] > 16.0 * std::numeric_limits<double>::epsilon() * std::max(std::abs(lo[d]), std::abs(hi[d])))) {
      out.message = "the points are flat along an axis: input rule returned unchanged";
      return out;
    }
  // Moments of the input in the Chebyshev basis of its bounding box, summed in
  // long double (as accurate_product does), one point at a time: the mass rules
  // have thousands of points, and their M x N matrix is never stored.
  std::vector<long double> mu(static_cast<size_t>(M), 0.0L);
  Eigen::VectorXd partial = Eigen::VectorXd::Zero(M);
  Eigen::Matrix<double, 3, Eigen::Dynamic> T(3, degree + 1);
  double total = 0.0;
  for (Eigen::Index j = 0; j < points.cols(); ++j) {
    double t[3];
    for (int d = 0; d < 3; ++d) t[d] = 2.0 * ((points(d, j) - lo[d]) / extent[d]) - 1.0;
    chebyshev_values(t, degree, T);
    const double w = weights[j];
    total += std::abs(w);
    int k = 0;
    for (int a = 0; a <= degree; ++a)
      for (int b = 0; a + b <= degree; ++b) {
        const double wab = w * T(0, a) * T(1, b);
        for (int c = 0; a + b + c <= degree; ++c) partial[k++] += wab * T(2, c);
      }
    // Sums of kMomentChunk terms in double (error <= kMomentChunk eps of their
    // absolute sum), then in long double: summing everything in long double cost
    // 11 % of the Hex20 cylinder's set-up (perf), for no accuracy that matters.
    if ((j + 1) % kMomentChunk == 0 || j + 1 == points.cols()) {
      for (int i = 0; i < M; ++i) mu[static_cast<size_t>(i)] += partial[i];
      partial.setZero();
    }
  }
  if (!(total > 0.0)) {
    out.message = "all weights are zero: input rule returned unchanged";
    return out;
  }
  Eigen::VectorXd moments(M);
  for (int k = 0; k < M; ++k) moments[k] = static_cast<double>(mu[static_cast<size_t>(k)]);
  const FittingPoints& F = fitting_points(degree);
  const Eigen::VectorXd w = F.lu.solve(moments);
  // Measured residual of the square system, in the same units as the LP's.
  const Eigen::MatrixXd V = vandermonde(F.points, degree);
  double worst = 0.0;
  for (int k = 0; k < M; ++k) {
    long double r = -mu[static_cast<size_t>(k)];
    for (int q = 0; q < M; ++q) r += static_cast<long double>(V(k, q)) * w[q];
    worst = std::max(worst, static_cast<double>(std::fabs(r)));
  }
  out.moment_residual = worst / total;
  out.points.resize(3, M);
  for (int q = 0; q < M; ++q)
    for (int d = 0; d < 3; ++d) out.points(d, q) = lo[d] + 0.5 * (F.points(d, q) + 1.0) * extent[d];
  out.weights = w;
  out.absolute_weight_ratio = w.cwiseAbs().sum() / std::abs(w.sum());
  out.fitted = true;
  out.message = fmt::format("fitted {} points to {} (sum |w| / |sum w| = {:.3g})", M, out.points_before,
                            out.absolute_weight_ratio);
  return out;
}

}  // namespace hofem
