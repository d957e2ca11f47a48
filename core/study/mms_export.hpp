#pragma once
// `hofem mms --export-matrix PREFIX`: the linear system of a manufactured-solution
// run as MatrixMarket files (io/matrix_market.hpp), to cross-check it in another
// code: PREFIX.mtx (K), PREFIX_rhs.mtx (b) and PREFIX_solution.mtx (hofem's u).
// The system is the one solved: Dirichlet DOFs (u = u* on the boundary) are
// eliminated, so K is K_ff over the free DOFs and b = f_f - K_fc u_c.
#include "problem/static_elasticity.hpp"
#include "study/manufactured_solution.hpp"

#include <string>

namespace hofem {

/// Writes the three files for a solved linear, serial case; throws
/// std::invalid_argument for a nonlinear (neohookean) or distributed one.
void export_mms_system(const MmsCase& c, const MmsProblem& p, const StaticElasticity& solved,
                       const std::string& prefix);

}  // namespace hofem
