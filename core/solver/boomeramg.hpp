#pragma once
// Algebraic multigrid preconditioner through hypre's BoomerAMG, configured for
// elasticity (three functions per node). PLACEHOLDER: being implemented.
#include "solver/preconditioner.hpp"

#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace hofem {

/// Names of the BoomerAMG configurations offered as preconditioners ("amg", ...).
std::vector<std::string> boomeramg_variant_names();
std::unique_ptr<Preconditioner> make_boomeramg_preconditioner(std::string_view variant);

}  // namespace hofem
