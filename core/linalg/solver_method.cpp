#include "linalg/solver_method.hpp"

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

std::optional<SolverMethod> method_named(std::string_view name) {
  for (const auto& [m, n] : kMethods)
    if (n == name) return m;
  return std::nullopt;
}

bool is_krylov_method(SolverMethod m) {
  return m == SolverMethod::Cg || m == SolverMethod::Cr || m == SolverMethod::Minres || m == SolverMethod::Gmres;
}

bool is_direct_method(SolverMethod m) {
  return m == SolverMethod::Cholmod || m == SolverMethod::Umfpack || m == SolverMethod::EigenLdlt;
}

}  // namespace hofem
