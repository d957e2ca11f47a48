#pragma once
// Simplification of a positive quadrature rule (Longva et al. 2020 §4.4): from N points
// with weights w0 >= 0, keep at most M = C(m+3, 3) of the same points with new
// positive weights that integrate every polynomial of total degree <= m exactly
// as the input rule does (up to rounding).
//
// Method (Longva et al. 2020 eq. 7-10): P (M x N) holds a tensor Chebyshev basis on the
// points' bounding box evaluated at the points; its SVD P = U S V^T gives the
// equivalent, perfectly conditioned constraints V_r^T w = V_r^T w0, w >= 0, whose
// basic feasible solutions have at most r = rank P <= M non-zeros.
//
// Two ways to a basic feasible point:
//  - active set (default): Lawson & Hanson's NNLS (1974, ch. 23) on the same
//    constraints, min |V_r^T w - c| over w >= 0. Its positive columns stay linearly
//    independent, so it ends on at most r points; its last least-squares solve on
//    them is the refinement. Measured on the cut cells of the Fig. 10 half ball
//    (Hex20, m = 6, 136 cells with N ~ 3500): 31 ms per cell against the simplex's
//    112 ms, at most 84 points, moment residual <= 1.7e-15 (Hex8, m = 4: 3.7 against
//    16.4 ms). Longva et al. 2020 solve eq. 10 as an LP; any basic feasible point is what it
//    asks for, and this is one, found faster.
//  - simplex: GLPK's dual simplex with a zero objective, then the weights on the
//    basic columns recomputed by least squares against the input's moments summed
//    in long double, and the better of GLPK's and the recomputed weights (smaller
//    residual, all > 0) kept. GLPK's own basic values come from an LU solve and
//    were already at rounding level in every case measured; the recomputation is
//    the safeguard for ill-conditioned bases. It is also the fallback whenever the
//    active-set answer is not accepted (not converged, or a residual above
//    max_moment_residual), so the active set can only make a run faster.
// The residual reported is measured, not assumed.
//
// Accuracy and cost of the simplex (measured, 2-core machine under load): moment
// residual 1e-16..7e-16 for tet-subdivided boxes and clipped cuboids at m = 1..10; a
// cluster of extent h at distance |x| from the origin carries only eps |x| / h of
// relative information in its coordinates, and a degenerate support (a vertex with
// fewer than r points) may meet the moments only to that level (2e-13 for
// h = 6e-4, m = 1). Time: m = 5, N = 672: 0.02 s; m = 8, N = 2208: 0.5 s;
// m = 10, N = 3800: ~2 s (the Jacobi SVD ~0.3 s, the rest the simplex).
//
// Robustness. Scaling the basis to the bounding box keeps P well conditioned for
// small clusters of points (cut cells with tiny intersections); flat or collinear
// point sets only lower the numerical rank r (axes of zero extent are handled).
// When GLPK fails (error code, or status not feasible), or the result misses
// `max_moment_residual`, the input rule is returned unchanged with
// simplified = false and `message` saying why — a numerical failure never throws,
// and the input rule is always a valid (only larger) answer. Bad arguments throw
// std::invalid_argument naming the argument.
//
// Threads. Debian's GLPK 5.0 is built re-entrant (glp_config("TLS") reports
// "_Thread_local"): every thread has its own GLPK environment and this function
// shares no problem object between calls, so it may be called from several
// threads at once. If the calling thread had no GLPK environment before the call,
// the function frees the one it created (GLPK's maintainers require each thread to
// free its environment before it ends); an environment the caller already had is
// left alone. GLPK's own internal errors (glp_error) abort the process; the
// inputs GLPK receives are validated here so that its API is never misused.
#include <Eigen/Core>

#include <string>

namespace hofem {

enum class SimplificationMethod {
  ActiveSet,  ///< Lawson-Hanson NNLS, the simplex as fallback (see above)
  Simplex,    ///< GLPK's dual simplex only
};

struct SimplificationOptions {
  SimplificationMethod method = SimplificationMethod::ActiveSet;
  /// Outer iterations of the active-set method (each adds one point); < 0: 3 r + 50
  /// (it typically needs ~r; measured 99 for r = 84). On reaching it, the simplex.
  int active_set_iterations = -1;
  /// Numerical rank of P: singular values below rank_tolerance * s_max count as
  /// zero. Directions that are exactly dependent on the point set (a flat or
  /// collinear set) come out of the SVD at ~eps * s_max; 1e-13 sits above that
  /// noise and far below the singular values of spread-out point sets (a 1e-3
  /// cluster in the bounding-box basis keeps full rank). Constraints dropped with
  /// small singular values can only cost accuracy, never feasibility, and
  /// moment_residual is measured with the full P, so any such cost is reported.
  double rank_tolerance = 1e-13;
  /// Accept the simplified rule only if its relative moment residual (see
  /// SimplifiedRule::moment_residual) is at most this; otherwise the input is
  /// returned. Conditioned inputs reach < 1e-15, clusters down to extent/|x| ~ 1e-4
  /// stay below 1e-12 (see above); a residual at GLPK's feasibility tolerance
  /// (1e-7) means the LP did not really solve, and is refused.
  double max_moment_residual = 1e-11;
  /// Active set only: orthonormal constraints by CholeskyQR2 and least squares by
  /// an updated QR (quadrature_simplification.cpp, "The fast path"): the same
  /// iterates as the SVD and a fresh pivoted QR per solve, in exact arithmetic,
  /// ~4x faster; the SVD path whenever P is ill-conditioned (kappa > 1e5) or a
  /// column is dependent. false: always the reference path (tests compare the two).
  bool fast = true;
};

struct SimplifiedRule {
  Eigen::MatrixXd points;      ///< 3 x n, a subset of the input points (same coordinates, bit for bit)
  Eigen::VectorXd weights;     ///< n, all > 0
  int points_before = 0;       ///< N
  int basis_size = 0;          ///< M = C(m+3, 3)
  int rank = 0;                ///< numerical rank r of P (0 if not computed)
  /// max_k |sum_j p_k(xi_j) (w_j - w0_j)| / sum_j |w0_j| over the Chebyshev basis
  /// of the bounding box (|p_k| <= 1 there); 0 when the input is returned.
  double moment_residual = 0.0;
  bool simplified = false;     ///< false: input returned unchanged (N <= M, or a failure described by `message`)
  std::string method;          ///< "active set" or "simplex": which method the kept rule comes from (if simplified)
  bool fast = false;           ///< the active set's answer came from the fast path (SimplificationOptions::fast)
  std::string message;
  int size() const { return static_cast<int>(weights.size()); }
};

/// Simplifies the rule (points 3 x N, any coordinates, e.g. a cell's reference
/// coordinates; weights N, >= 0) for strength `degree` >= 0; see above.
/// Throws std::invalid_argument for a size mismatch, negative or non-finite
/// weights, non-finite points or a negative degree.
SimplifiedRule simplify_quadrature(const Eigen::MatrixXd& points, const Eigen::VectorXd& weights, int degree,
                                   const SimplificationOptions& options = {});

/// M = C(m+3, 3), the number of polynomials of total degree <= m in 3D.
int polynomial_space_dimension(int degree);


/// Moment fitting, the cheap alternative for rules that only need to be exact
/// (Longva et al. 2020 §4.4 motivate the LP by positivity and by points inside
/// the geometry; a rule used only for integrands of degree <= m on an affine cell,
/// as the finite-cell mass rules are, needs neither). The points are fixed: M =
/// C(m+3, 3) approximate Fekete points (Sommariva & Vianello 2009, §2) of
/// [-1, 1]^3 mapped onto the input points' bounding box; the weights solve the
/// square moment system in the Chebyshev basis of that box (the basis of the LP,
/// chebyshev_matrix), so every polynomial of total degree <= m is integrated as
/// the input rule integrates it, to rounding (moment_residual, measured).
/// Weights may be negative and points may lie outside the geometry (inside its
/// bounding box): cost O(N M) for the moments plus O(M^2) for the solve with a
/// factorisation made once per degree, against the LP's O(N M^2).
struct FittedRule {
  Eigen::MatrixXd points;            ///< 3 x M (or the input, if not fitted)
  Eigen::VectorXd weights;           ///< M, of either sign
  int points_before = 0;             ///< N
  double moment_residual = 0.0;      ///< as SimplifiedRule::moment_residual (relative to sum |w0|)
  double absolute_weight_ratio = 0;  ///< sum |w| / |sum w| (1 for positive weights): rounding amplification
  bool fitted = false;               ///< false: input returned (N <= M, flat points, zero weights)
  std::string message;
  int size() const { return static_cast<int>(weights.size()); }
};
/// Throws std::invalid_argument as simplify_quadrature does.
FittedRule fit_quadrature(const Eigen::MatrixXd& points, const Eigen::VectorXd& weights, int degree);
/// The 2-norm condition number of the fitting points' square Chebyshev-Vandermonde matrix.
double fitting_condition(int degree);

}  // namespace hofem
