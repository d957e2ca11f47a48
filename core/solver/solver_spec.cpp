#include "solver/solver_spec.hpp"

#include "solver/preconditioner.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <array>
#include <stdexcept>
#include <utility>

namespace hofem {

namespace {

constexpr std::array<std::pair<SolverMethod, std::string_view>, 8> kMethods{{
    {SolverMethod::Cholmod, "cholmod"},
    {SolverMethod::Umfpack, "umfpack"},
    {SolverMethod::EigenLdlt, "eigen-ldlt"},
    {SolverMethod::HyprePcg, "hypre-pcg"},
    {SolverMethod::Cg, "cg"},
    {SolverMethod::Cr, "cr"},
    {SolverMethod::Minres, "minres"},
    {SolverMethod::Gmres, "gmres"},
}};

}  // namespace

std::string_view method_name(SolverMethod method) {
  for (const auto& [m, name] : kMethods)
    if (m == method) return name;
  throw std::logic_error("method_name: unknown SolverMethod");
}

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

bool SolverSpec::is_krylov() const {
  return method == SolverMethod::Cg || method == SolverMethod::Cr || method == SolverMethod::Minres ||
         method == SolverMethod::Gmres;
}

bool SolverSpec::is_direct() const {
  return method == SolverMethod::Cholmod || method == SolverMethod::Umfpack || method == SolverMethod::EigenLdlt;
}

std::string SolverSpec::name() const {
  if (!method) return "auto";
  const std::string m(method_name(*method));
  return preconditioner.empty() ? m : m + "+" + preconditioner;
}

std::string linear_solver_choices() {
  return fmt::format("auto, cholmod, umfpack, eigen-ldlt, hypre-pcg+amg, or <cg|cr|minres|gmres>+<{}>",
                     fmt::join(preconditioner_names(), "|"));
}

SolverSpec SolverSpec::parse(std::string_view name) {
  SolverSpec spec;
  if (name == "auto") return spec;
  if (std::ranges::count(linear_solver_names(), name) == 0)
    throw std::invalid_argument(fmt::format("unknown linear solver '{}' (valid: {})", name, linear_solver_choices()));
  const size_t plus = name.find('+');
  const std::string_view method = name.substr(0, plus);
  for (const auto& [m, n] : kMethods)
    if (n == method) spec.method = m;
  if (plus != std::string_view::npos) spec.preconditioner = std::string(name.substr(plus + 1));
  return spec;
}

}  // namespace hofem
