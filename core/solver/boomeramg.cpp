#include "solver/boomeramg.hpp"

#include <stdexcept>

namespace hofem {

std::vector<std::string> boomeramg_variant_names() { return {}; }
std::unique_ptr<Preconditioner> make_boomeramg_preconditioner(std::string_view) {
  throw std::logic_error("BoomerAMG not implemented yet");
}

}  // namespace hofem
