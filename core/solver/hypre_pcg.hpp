#pragma once
// hypre's own PCG with BoomerAMG, for comparison with our CG + "amg".
// PLACEHOLDER: being implemented.
#include "solver/linear_solver.hpp"

#include <memory>

namespace hofem {

std::unique_ptr<LinearSolver> make_hypre_pcg_solver();

}  // namespace hofem
