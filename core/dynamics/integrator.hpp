#pragma once
// Time integrators of the dynamics layer (thesis §2.3, eq. 2.15-2.28):
//   explicit-euler     x+ = x + h v,  v+ = v + h a(x, v)                 order 1
//   symplectic-euler   v+ = v + h a(x, v),  x+ = x + h v+                 order 1
//   leapfrog           velocity Verlet (kick-drift-kick)                  order 2
//   rk4                classical Runge-Kutta on (x, v)                    order 4
//   semi-implicit      Baraff & Witkin (1998): one linearised backward-Euler
//                      step, (M + h D + h^2 K) dv = h (f + h df/dx v)    order 1
//   implicit-euler     minimisation of the incremental potential (thesis 2.25)
//                      by Newton with line search                        order 1
// The explicit ones never assemble a Hessian.
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace hofem {

enum class Integrator { ExplicitEuler, SymplecticEuler, Leapfrog, RK4, SemiImplicit, ImplicitEuler };

/// A row of the one table of integrators (integrator.cpp): the scene reader,
/// --help, the scene schema and the verification's order checks read it.
struct IntegratorEntry {
  Integrator integrator;
  std::string_view name;         ///< as scene files spell it
  std::string_view description;
  int order;                     ///< convergence order in dt (what the verification asserts)
  bool is_explicit;              ///< never assembles a Hessian
  double stability_limit;        ///< h omega_max of an undamped oscillator; 0: none stable, inf: no limit
};

/// Every integrator, in the order above.
std::span<const IntegratorEntry> integrator_registry();

/// Scene-file names, in the order above.
std::vector<std::string> integrator_names();
/// Throws std::invalid_argument naming the valid choices.
Integrator parse_integrator(std::string_view name);
std::string_view integrator_name(Integrator integrator);
bool is_explicit(Integrator integrator);
/// Convergence order in dt of the integrator (what the verification asserts).
int integrator_order(Integrator integrator);
/// Stability limit h * omega_max of an undamped linear oscillator, 0 if none
/// exists: explicit Euler amplifies every undamped mode by sqrt(1 + (h omega)^2)
/// per step, so it is unstable at any dt; symplectic Euler and leapfrog are
/// stable for h omega < 2, RK4 for h omega < 2 sqrt(2); the implicit ones have
/// no limit (infinity).
double stability_limit(Integrator integrator);

}  // namespace hofem
