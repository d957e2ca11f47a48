#include "run_verification.hpp"

#include "basis_checks.hpp"
#include "convergence_checks.hpp"
#include "dynamics_checks.hpp"
#include "embedded_checks.hpp"
#include "element_checks.hpp"
#include "fcm_conditioning_checks.hpp"
#include "fcm_convergence_checks.hpp"
#include "fcm_load_checks.hpp"
#include "fcm_rigid_motion_checks.hpp"
#include "material_checks.hpp"
#include "partition_checks.hpp"
#include "quadrature_checks.hpp"
#include "solver_checks.hpp"

namespace hofem::verification {

Report run_fast_checks() {
  Report report;
  add_quadrature_checks(report);
  add_basis_checks(report);
  add_material_checks(report);
  add_element_checks(report);
  add_patch_checks(report);
  add_dynamics_checks(report);
  add_embedded_quadrature_checks(report);
  add_fcm_load_checks(report);
  add_partition_checks(report);
  return report;
}

Report run_all_checks(const SuiteOptions& options) {
  Report report = run_fast_checks();
  if (options.solvers) add_solver_checks(report);
  if (options.convergence != "none") add_convergence_checks(report, options.convergence);
  // The finite cell method's figures (second seed Fig. 5, 6, 10): seconds to a minute.
  if (options.convergence != "none") {
    add_fcm_conditioning_checks(report, options.convergence);
    add_fcm_rigid_motion_checks(report);
    add_fcm_convergence_checks(report, options.convergence);
  }
  return report;
}

}  // namespace hofem::verification
