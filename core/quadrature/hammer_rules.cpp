#include "quadrature/hammer_rules.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

namespace hofem {

namespace {

// Builds a rule from barycentric points (lambda_0 .. lambda_d) and weights that
// sum to 1, scaling the weights by the reference volume. The unit-simplex
// coordinates are x_i = lambda_i (i >= 1).
template <int NB>
QuadratureRule from_barycentric(CellType cell, int degree, const char* source,
                                const std::vector<std::array<double, NB>>& bary,
                                const std::vector<double>& w) {
  QuadratureRule q;
  q.cell = cell;
  q.degree = degree;
  q.family = RuleFamily::Hammer;
  q.source = source;
  q.id = fmt::format("hammer-{}", bary.size());
  q.claimed_quality = std::ranges::all_of(w, [](double x) { return x > 0; }) ? "PI" : "NI";
  const int n = static_cast<int>(bary.size());
  q.points.resize(NB - 1, n);
  q.weights.resize(n);
  for (int k = 0; k < n; ++k) {
    for (int i = 1; i < NB; ++i) q.points(i - 1, k) = bary[k][i];
    q.weights[k] = w[k] * reference_volume(cell);
  }
  return q;
}

std::vector<QuadratureRule> triangle_rules() {
  using B = std::array<double, 3>;
  const double t = 1.0 / 3.0;
  std::vector<QuadratureRule> rules;
  rules.push_back(from_barycentric<3>(CellType::Triangle, 1, "Hammer 1-point (thesis Table 4)", {B{t, t, t}}, {1.0}));
  const double a = 2.0 / 3.0, b = 1.0 / 6.0;
  rules.push_back(from_barycentric<3>(CellType::Triangle, 2, "Hammer 3-point (thesis Table 4)",
                                      {B{a, b, b}, B{b, a, b}, B{b, b, a}}, {t, t, t}));
  // 4-point degree-3 rule: centroid weight -27/48 (negative), orbit (3/5,1/5,1/5) 25/48.
  rules.push_back(from_barycentric<3>(CellType::Triangle, 3, "Hammer 4-point (thesis Table 4; negative weight)",
                                      {B{t, t, t}, B{0.6, 0.2, 0.2}, B{0.2, 0.6, 0.2}, B{0.2, 0.2, 0.6}},
                                      {-27.0 / 48.0, 25.0 / 48.0, 25.0 / 48.0, 25.0 / 48.0}));
  // 7-point degree-5 rule (Radon 1948). Table 4 prints 10 digits; these are the
  // exact values: alpha_{1,2} = (9 -+ 2 sqrt15)/21, beta_{1,2} = (6 +- sqrt15)/21,
  // weights 9/40 and (155 +- sqrt15)/1200.
  const double s15 = std::sqrt(15.0);
  const double a1 = (9.0 - 2.0 * s15) / 21.0, b1 = (6.0 + s15) / 21.0;
  const double a2 = (9.0 + 2.0 * s15) / 21.0, b2 = (6.0 - s15) / 21.0;
  const double w1 = (155.0 + s15) / 1200.0, w2 = (155.0 - s15) / 1200.0;
  rules.push_back(from_barycentric<3>(
      CellType::Triangle, 5, "Hammer/Radon 7-point (thesis Table 4, exact values)",
      {B{t, t, t}, B{a1, b1, b1}, B{b1, a1, b1}, B{b1, b1, a1}, B{a2, b2, b2}, B{b2, a2, b2}, B{b2, b2, a2}},
      {9.0 / 40.0, w1, w1, w1, w2, w2, w2}));
  return rules;
}

// Thesis Table 5 repeats the *triangle* coordinates for the tetrahedron, which
// is wrong (they are not even points of a tet in barycentric form). These are
// the actual Hammer–Marlowe–Stroud tetrahedron rules:
//   1 point:  centroid (degree 1);
//   4 points: orbit of (a, b, b, b), a = (5 + 3 sqrt5)/20, b = (5 - sqrt5)/20, weights 1/4 (degree 2);
//   5 points: centroid -4/5, orbit of (1/2, 1/6, 1/6, 1/6) 9/20 (degree 3, negative weight).
std::vector<QuadratureRule> tetrahedron_rules() {
  using B = std::array<double, 4>;
  std::vector<QuadratureRule> rules;
  rules.push_back(from_barycentric<4>(CellType::Tetrahedron, 1, "Hammer 1-point (thesis Table 5)",
                                      {B{0.25, 0.25, 0.25, 0.25}}, {1.0}));
  const double s5 = std::sqrt(5.0);
  const double a = (5.0 + 3.0 * s5) / 20.0, b = (5.0 - s5) / 20.0;
  rules.push_back(from_barycentric<4>(CellType::Tetrahedron, 2, "Hammer 4-point (thesis Table 5, corrected)",
                                      {B{a, b, b, b}, B{b, a, b, b}, B{b, b, a, b}, B{b, b, b, a}},
                                      {0.25, 0.25, 0.25, 0.25}));
  const double h = 0.5, s = 1.0 / 6.0;
  rules.push_back(from_barycentric<4>(
      CellType::Tetrahedron, 3, "Hammer 5-point (thesis Table 5, corrected; negative weight)",
      {B{0.25, 0.25, 0.25, 0.25}, B{h, s, s, s}, B{s, h, s, s}, B{s, s, h, s}, B{s, s, s, h}},
      {-0.8, 0.45, 0.45, 0.45, 0.45}));
  return rules;
}

}  // namespace

std::vector<QuadratureRule> hammer_rules(CellType cell) {
  if (cell == CellType::Triangle) return triangle_rules();
  if (cell == CellType::Tetrahedron) return tetrahedron_rules();
  throw std::invalid_argument("hammer_rules: only triangle and tetrahedron have Hammer rules");
}

}  // namespace hofem
