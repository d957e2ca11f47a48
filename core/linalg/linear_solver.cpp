#include "linalg/linear_solver.hpp"

#include <fmt/format.h>

#include <stdexcept>

namespace hofem {

void apply_iteration_budget(LinearSolver& solver, int k) {
  if (k > 0 && !solver.set_fixed_iterations(k))
    throw std::invalid_argument(fmt::format("krylov_iterations = {} needs a Krylov solver, not {}", k, solver.name()));
}

}  // namespace hofem
