#include "solver/solver_spec.hpp"

#include "linalg/boomeramg_variants.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <stdexcept>
#include <utility>

namespace hofem {

void validate(const DistributedSolverOptions& o) {
  if (o.krylov != "pcg" && o.krylov != "gmres")
    throw std::invalid_argument(fmt::format("distributed solver: unknown Krylov method '{}' (pcg, gmres)", o.krylov));
  const std::vector<std::string> variants = boomeramg_variant_names();
  if (std::find(variants.begin(), variants.end(), o.amg) == variants.end())
    throw std::invalid_argument(
        fmt::format("distributed solver: unknown BoomerAMG variant '{}' (valid: {})", o.amg, fmt::join(variants, ", ")));
  if (o.gmres_restart < 1)
    throw std::invalid_argument(fmt::format("distributed solver: GMRES restart must be >= 1 (got {})", o.gmres_restart));
}

std::string SolverSpec::name() const {
  if (!method) return "auto";
  const std::string m(method_name(*method));
  return preconditioner.empty() ? m : m + "+" + preconditioner;
}

SolverSpec SolverSpec::parse(std::string_view name) {
  SolverSpec spec;
  if (name == "auto") return spec;
  if (std::ranges::count(linear_solver_names(), name) == 0)
    throw std::invalid_argument(fmt::format("unknown linear solver '{}' (valid: {})", name, linear_solver_choices()));
  const size_t plus = name.find('+');
  const std::string_view method = name.substr(0, plus);
  spec.method = method_named(method);
  if (plus != std::string_view::npos) spec.preconditioner = std::string(name.substr(plus + 1));
  return spec;
}

}  // namespace hofem
