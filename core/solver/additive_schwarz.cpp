#include "solver/additive_schwarz.hpp"

#include <stdexcept>

namespace hofem {

std::unique_ptr<Preconditioner> make_additive_schwarz_preconditioner() {
  throw std::logic_error("schwarz not implemented yet");
}

}  // namespace hofem
