#include "solver/hypre_pcg.hpp"

#include <stdexcept>

namespace hofem {

std::unique_ptr<LinearSolver> make_hypre_pcg_solver() { throw std::logic_error("hypre PCG not implemented yet"); }

}  // namespace hofem
