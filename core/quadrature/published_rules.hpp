#pragma once
// Published symmetric rules on the triangle and tetrahedron, carried over as data
// (core/quadrature/rules/<cell>/<REF>-<degree>-<points>.yml, source cited in each
// file) and embedded into the library at build time.
//
// File format (the compact orbit format of spraetor/FiniteElementQuadratureRules.jl):
//   '#' comment lines (citation and provenance), then
//   reference: 'WV15'      region: simplex      dim: 2|3       degree: <claimed>
//   orbits: [n_0, n_1, ...]   number of orbits of each symmetry type, in the order
//       triangle:     S3, S21, S111, A3 (rotation triple), M12, M13, M23 (mirror
//                     pairs swapping two barycentrics), I (single point, 3 args)
//       tetrahedron:  S4, S31, S22, S211, S1111
//   positions: list of barycentric orbit parameters, consumed orbit by orbit
//   weights:   one weight per orbit, normalised so the rule's weights sum to 1
//              (optional: Witherden–Vincent files omit them; we then solve the
//              moment equations for them, as the data's own library does)
#include "quadrature/quadrature_rule.hpp"

#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace hofem {

/// Malformed rule data: the message names the origin (file) and the line.
class RuleFormatError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Parses and expands one rule file. `origin` names it in error messages.
/// Throws RuleFormatError on malformed input (unknown key, bad number, orbit
/// counts that do not match the positions or weights, wrong dimension).
QuadratureRule parse_published_rule(std::string_view text, std::string_view origin);

/// Every embedded published rule for a cell (triangle or tetrahedron).
std::vector<QuadratureRule> published_rules(CellType cell);

}  // namespace hofem
