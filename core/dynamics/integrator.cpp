#include "dynamics/integrator.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace hofem {

namespace {

// The one table of the integrators (thesis §2.3): the scene-file name, what it
// is, its order in dt and its stability limit h omega_max on an undamped linear
// oscillator (0: unstable at any dt, infinity: none). Explicit Euler amplifies
// every undamped mode by sqrt(1 + (h omega)^2) per step; symplectic Euler and
// leapfrog are stable for h omega < 2, RK4 for h omega < 2 sqrt(2).
// Function-local (not a namespace-scope table): read during other files'
// static initialisation too, and sqrt is not a constant expression.
std::span<const IntegratorEntry> table() {
  constexpr double kNoLimit = std::numeric_limits<double>::infinity();
  static const std::array<IntegratorEntry, 6> integrators{{
      {Integrator::ExplicitEuler, "explicit-euler", "forward Euler on (x, v)", 1, true, 0.0},
      {Integrator::SymplecticEuler, "symplectic-euler", "velocity first, then position with the new velocity", 1, true,
       2.0},
      {Integrator::Leapfrog, "leapfrog", "velocity Verlet (kick-drift-kick)", 2, true, 2.0},
      {Integrator::RK4, "rk4", "classical Runge-Kutta on (x, v)", 4, true, 2.0 * std::sqrt(2.0)},
      {Integrator::SemiImplicit, "semi-implicit", "Baraff and Witkin (1998): one linearised backward-Euler step", 1,
       false, kNoLimit},
      {Integrator::ImplicitEuler, "implicit-euler",
       "backward Euler as minimisation of the incremental potential, Newton with line search", 1, false, kNoLimit},
  }};
  return integrators;
}

const IntegratorEntry& entry(Integrator integrator) {
  for (const IntegratorEntry& e : table())
    if (e.integrator == integrator) return e;
  throw std::logic_error("integrator: unknown Integrator");
}

}  // namespace

std::span<const IntegratorEntry> integrator_registry() { return table(); }

std::string_view integrator_name(Integrator integrator) { return entry(integrator).name; }

std::vector<std::string> integrator_names() {
  std::vector<std::string> names;
  for (const IntegratorEntry& e : table()) names.emplace_back(e.name);
  return names;
}

Integrator parse_integrator(std::string_view name) {
  for (const IntegratorEntry& e : table())
    if (e.name == name) return e.integrator;
  throw std::invalid_argument(
      fmt::format("unknown integrator '{}' (valid: {})", name, fmt::join(integrator_names(), ", ")));
}

bool is_explicit(Integrator integrator) { return entry(integrator).is_explicit; }

int integrator_order(Integrator integrator) { return entry(integrator).order; }

double stability_limit(Integrator integrator) { return entry(integrator).stability_limit; }

}  // namespace hofem
