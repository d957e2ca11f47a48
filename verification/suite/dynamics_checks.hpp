#pragma once
// Dynamics (thesis §2.3):
//  - dynamics.order:    convergence order in dt of every integrator against the
//                       exact modal solution of a linear-elastic bar (lumped mass);
//  - dynamics.momentum: linear momentum of a free spinning Neo-Hookean body kept to
//                       rounding by every integrator, angular momentum by the
//                       symplectic ones;
//  - dynamics.energy:   bounded energy (no drift) for symplectic Euler and leapfrog
//                       over 4000 steps, monotone decay for implicit Euler;
//  - dynamics.stability: each explicit integrator's stable-dt estimate against
//                       its published h omega limit over the exact omega_max, and
//                       runs just inside (bounded) and just outside (growing);
//  - dynamics.mass:     lumped masses (row-sum / HRZ) positive and summing to rho V.
#include "report.hpp"

#include "dynamics/dynamic_elasticity.hpp"

#include <memory>

namespace hofem::verification {

/// Relative L2 error of the free displacement at t = 0.75 T (T the bar's lowest
/// period) after `steps` steps of the integrator, against the modal solution.
double bar_vibration_error(Integrator integrator, int steps);

/// A free Neo-Hookean unit cube (Tet4, 2 cells per side, E = 1e4, rho = 100,
/// lumped mass) spinning about (0.3, -0.5, 1), translating and stretching.
struct FreeBody {
  Mesh mesh;
  std::unique_ptr<Material> material;
  FreeBody();
  std::unique_ptr<DynamicElasticity> simulation(Integrator integrator, double dt) const;
};

void add_dynamics_checks(Report& report);

}  // namespace hofem::verification
