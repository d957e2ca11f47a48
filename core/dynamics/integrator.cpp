#include "dynamics/integrator.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <cmath>
#include <limits>
#include <stdexcept>

namespace hofem {

namespace {
constexpr Integrator kAll[] = {Integrator::ExplicitEuler, Integrator::SymplecticEuler, Integrator::Leapfrog,
                               Integrator::RK4,           Integrator::SemiImplicit,    Integrator::ImplicitEuler};
}  // namespace

std::string_view integrator_name(Integrator integrator) {
  switch (integrator) {
    case Integrator::ExplicitEuler: return "explicit-euler";
    case Integrator::SymplecticEuler: return "symplectic-euler";
    case Integrator::Leapfrog: return "leapfrog";
    case Integrator::RK4: return "rk4";
    case Integrator::SemiImplicit: return "semi-implicit";
    case Integrator::ImplicitEuler: return "implicit-euler";
  }
  return "?";
}

std::vector<std::string> integrator_names() {
  std::vector<std::string> names;
  for (Integrator i : kAll) names.emplace_back(integrator_name(i));
  return names;
}

Integrator parse_integrator(std::string_view name) {
  for (Integrator i : kAll)
    if (integrator_name(i) == name) return i;
  throw std::invalid_argument(
      fmt::format("unknown integrator '{}' (valid: {})", name, fmt::join(integrator_names(), ", ")));
}

bool is_explicit(Integrator integrator) {
  return integrator != Integrator::SemiImplicit && integrator != Integrator::ImplicitEuler;
}

int integrator_order(Integrator integrator) {
  switch (integrator) {
    case Integrator::Leapfrog: return 2;
    case Integrator::RK4: return 4;
    default: return 1;
  }
}

double stability_limit(Integrator integrator) {
  switch (integrator) {
    case Integrator::ExplicitEuler: return 0.0;
    case Integrator::SymplecticEuler:
    case Integrator::Leapfrog: return 2.0;
    case Integrator::RK4: return 2.0 * std::sqrt(2.0);
    default: return std::numeric_limits<double>::infinity();
  }
}

}  // namespace hofem
