#pragma once
// Element-block Additive-Schwarz preconditioner (second seed eq. 13-14).
// PLACEHOLDER: being implemented.
#include "solver/preconditioner.hpp"

#include <memory>

namespace hofem {

std::unique_ptr<Preconditioner> make_additive_schwarz_preconditioner();

}  // namespace hofem
