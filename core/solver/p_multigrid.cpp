#include "solver/p_multigrid.hpp"

#include <stdexcept>

namespace hofem {

std::unique_ptr<Preconditioner> make_p_multigrid_preconditioner() { throw std::logic_error("pmg not implemented yet"); }

}  // namespace hofem
