#pragma once
// Embedded quadrature, Longva et al. 2020 §4.6 / Fig. 4: a rotated, translated cuboid
// (1.1 x 0.8 x 0.6, 48 tetrahedra) inside the reference hex [-1, 1]^3; the clipped
// rule of strength m over (cuboid ∩ cell) (§4.5) and its LP simplification (§4.4)
// integrate every monomial of degree <= m of the cuboid's local frame, against
// the analytic integrals. Two cases: one cell [-1, 1]^3 (the cuboid whole inside),
// and the 8 octants of [-1, 1]^3 (the cuboid cut by the cell planes; each cell's
// rule is simplified in that cell's reference coordinates, and the cells summed).
// Group "embedded.fig4".
#include "embedded/quadrature_simplification.hpp"
#include "report.hpp"

#include <array>
#include <string>
#include <vector>

namespace hofem::verification {

/// One case and strength of the study, with the error of every monomial.
struct Fig4Result {
  std::string geometry;  ///< "one cell" or "8 octants", and the method: "one cell, active set"
  int degree = 0;        ///< strength m
  int basis_size = 0;    ///< M = C(m+3, 3)
  int points_before = 0, points_after = 0;  ///< summed over cells
  int max_points_after_per_cell = 0;
  double min_weight_ratio = 0.0;  ///< min over cells of (min weight / mean weight) of the simplified rule
  double max_outside = 0.0;       ///< largest distance of a kept point outside the cuboid, / cuboid diameter
  double seconds = 0.0;           ///< simplification time, summed over cells
  int failures = 0;               ///< cells whose simplification returned the input (N > M)
  int fallbacks = 0;              ///< active set: cells whose answer came from the simplex fallback
  struct Monomial {
    std::array<int, 3> exponent;  ///< of the local coordinates y (each in [0.2, 0.2 + extent])
    double initial_error = 0.0;   ///< |Q - I| / I of the clipped rule (I > 0 analytic)
    double simplified_error = 0.0;
  };
  std::vector<Monomial> monomials;  ///< all of degree <= m (the Fig. 4 scatter)
  double max_initial_error() const;
  double max_simplified_error() const;
};

/// Runs one case (octants = false: one cell) for strength m with one way to the
/// basic feasible point (quadrature_simplification.hpp).
Fig4Result fig4_study(bool octants, int degree, SimplificationMethod method);

void add_embedded_quadrature_checks(Report& report);

}  // namespace hofem::verification
