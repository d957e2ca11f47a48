#pragma once
// p-multigrid V-cycle for element orders >= 2. PLACEHOLDER: being implemented.
#include "solver/preconditioner.hpp"

#include <memory>

namespace hofem {

std::unique_ptr<Preconditioner> make_p_multigrid_preconditioner();

}  // namespace hofem
