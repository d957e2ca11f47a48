#pragma once
// Per-element quadrature for cut cells (finite cell method, Longva et al. 2020 §4.5):
// each element may integrate with its own points instead of the standard rule.
// Two families, because stiffness and mass need different strengths (§6).
//
// Convention of every entry: null = the element's standard rule; a rule with no
// points = the element contributes nothing (the geometry misses the cell, or the
// cell was dropped, §5.3). An empty vector = standard rules everywhere.
#include "basis/basis_tabulation.hpp"

#include <memory>
#include <vector>

namespace hofem {

using ElementQuadratureList = std::vector<std::shared_ptr<const ElementQuadrature>>;

struct ElementRules {
  ElementQuadratureList stiffness;  ///< energy, forces, Hessian, element volumes
  ElementQuadratureList mass;       ///< mass matrices, lumped mass, body loads
  bool empty() const { return stiffness.empty() && mass.empty(); }
};

}  // namespace hofem
