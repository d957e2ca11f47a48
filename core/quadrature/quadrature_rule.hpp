#pragma once
// A quadrature rule on a reference cell: points (one column each, reference
// coordinates of cell_type.hpp), weights, the degree of exactness and where it
// comes from. Positivity and interiority are *measured* from the data when the
// rule is made (never taken from a published label — some are wrong).
#include "quadrature/cell_type.hpp"

#include <Eigen/Core>

#include <string>

namespace hofem {

/// Family a rule belongs to, used when a query prefers one over another.
// Declaration order is the query's preference on ties (later = preferred).
enum class RuleFamily {
  GaussTensor,     ///< tensor product of 1D Gauss–Legendre (segment, quad, hex)
  GaussCollapsed,  ///< Stroud conical product of Gauss–Jacobi rules (triangle, tet)
  Hammer,          ///< Hammer/Radon rules of the thesis appendix (Tables 4–5)
  Published,       ///< published symmetric rules carried over as data
};

std::string_view name(RuleFamily family);

/// Smallest margin from the boundary (see interior_margin) for a point to count
/// as strictly inside. Published rules with points "on" the boundary store a zero
/// that rounds to margins of ~1e-16; every other point of the rules we carry sits
/// at least 6e-10 inside (the closest: Witherden–Vincent's degree-9 tetrahedron
/// rule). 1e-12 separates the two classes by more than two orders of magnitude
/// each way. Points close to the boundary are penalised separately: the rule
/// query prefers, among rules with equal point counts, the larger margin.
inline constexpr double kInteriorTolerance = 1e-12;

struct QuadratureRule {
  CellType cell = CellType::Segment;
  int degree = 0;          ///< claimed degree of exactness (verified by the test suite)
  RuleFamily family = RuleFamily::GaussTensor;
  std::string id;          ///< short identifier, e.g. "WV15-8-46", "hammer-7", "collapsed-n4"
  std::string source;      ///< citation / construction
  /// What the rule's source or construction claims: 'P'/'N' positive/negative
  /// weights, then 'I'/'B'/'O' points inside/on the boundary/outside. Checked by
  /// the verification suite, never trusted by the code.
  std::string claimed_quality;
  Eigen::MatrixXd points;  ///< dim x n, reference coordinates
  Eigen::VectorXd weights; ///< n, sum = reference_volume(cell)

  int size() const { return static_cast<int>(weights.size()); }
  int dim() const { return static_cast<int>(points.rows()); }
  double min_weight() const { return weights.minCoeff(); }
  /// Smallest interior_margin over all points.
  double min_interior_margin() const;
  bool all_weights_positive() const { return min_weight() > 0.0; }
  bool all_points_interior() const { return min_interior_margin() > kInteriorTolerance; }
  bool positive_interior() const { return all_weights_positive() && all_points_interior(); }
};

}  // namespace hofem
