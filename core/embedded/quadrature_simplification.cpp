#include "embedded/quadrature_simplification.hpp"

#include <Eigen/QR>
#include <Eigen/SVD>
#include <fmt/format.h>
#include <glpk.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>
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
    for (int a = 0; a <= m; ++a)
      for (int b = 0; a + b <= m; ++b)
        for (int c = 0; a + b + c <= m; ++c) P(k++, j) = T(0, a) * T(1, b) * T(2, c);
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

// Lawson & Hanson (1974), "Solving Least Squares Problems", ch. 23: the active-set
// method for min |A w - c| over w >= 0. Its passive (positive) columns stay
// linearly independent, so it ends with at most rank(A) = r positive weights: when
// c lies in the cone of A's columns (it does: w0 >= 0 is a solution), a basic
// feasible point of eq. 10, the same kind of answer as the simplex's.
struct ActiveSetResult {
  std::vector<int> support;
  Eigen::VectorXd weights;
  bool converged = false;
};

ActiveSetResult active_set_nnls(const Eigen::MatrixXd& A, const Eigen::VectorXd& c, int max_iterations) {
  const Eigen::Index n = A.cols();
  std::vector<char> passive(static_cast<size_t>(n), 0);
  std::vector<int> P;
  Eigen::VectorXd w = Eigen::VectorXd::Zero(n), r = c, z;
  // A's rows are orthonormal (|A^T r| <= |r|): a gradient below this is rounding
  // of a residual at the level of eps |c| per column summed over the N columns.
  const double tolerance = 16.0 * std::numeric_limits<double>::epsilon() * c.norm() * std::sqrt(static_cast<double>(n));
  ActiveSetResult out;
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
    passive[static_cast<size_t>(best)] = 1;
    P.push_back(static_cast<int>(best));
    // Inner loop: step from w towards the unconstrained solution z on P as far as
    // w stays >= 0, drop the columns that reach zero, and solve again.
    bool positive = false;
    for (size_t inner = 0; inner <= P.size() && !P.empty(); ++inner) {
      z = solve_on(A, c, P);  // argmin |A_P z - c|
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
      P = std::move(kept);
    }
    if (positive)
      for (size_t k = 0; k < P.size(); ++k) w[P[k]] = z[static_cast<Eigen::Index>(k)];
    r = c;
    for (const int j : P) r -= w[j] * A.col(j);
  }
  out.support = P;
  out.weights = w(P);
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
  const Eigen::VectorXd Pw0 = accurate_product(P, w0);
  const double scale = w0.sum();
  const Eigen::MatrixXd Vr = right_singular_vectors(P, options.rank_tolerance, out.rank);
  const Eigen::MatrixXd A = Vr.transpose();
  const Eigen::VectorXd c = accurate_product(A, w0);
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
    const ActiveSetResult nn = active_set_nnls(A, c, iterations);
    const bool positive = !nn.support.empty() && (nn.weights.array() > 0.0).all();
    const double residual = positive ? moment_residual(P, Pw0, scale, nn.support, nn.weights) : kInfinity;
    if (nn.converged && residual <= options.max_moment_residual)
      return accept(nn.support, nn.weights, residual, "active set", "");
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

}  // namespace hofem
