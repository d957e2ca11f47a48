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
#include "study_checks.hpp"
#include "material_checks.hpp"
#include "partition_checks.hpp"
#include "quadrature_checks.hpp"
#include "solver_checks.hpp"

#include <chrono>

namespace hofem::verification {

namespace {

/// Runs one family of checks and records its wall time as a measurement of the
/// group "timing" (the main job's budget is accounted per family: DEVELOPERS.md).
template <class AddChecks>
void timed(Report& report, const char* family, AddChecks&& add) {
  const auto t0 = std::chrono::steady_clock::now();
  add();
  report.measure("timing", family, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(),
                 "wall seconds of this family of checks");
}

}  // namespace

Report run_fast_checks() {
  Report report;
  timed(report, "quadrature", [&] { add_quadrature_checks(report); });
  timed(report, "basis", [&] { add_basis_checks(report); });
  timed(report, "material", [&] { add_material_checks(report); });
  timed(report, "element", [&] { add_element_checks(report); });
  timed(report, "patch", [&] { add_patch_checks(report); });
  timed(report, "dynamics", [&] { add_dynamics_checks(report); });
  timed(report, "embedded quadrature (Fig. 4)", [&] { add_embedded_quadrature_checks(report); });
  timed(report, "embedded loads", [&] { add_fcm_load_checks(report); });
  timed(report, "partition", [&] { add_partition_checks(report); });
  return report;
}

Report run_all_checks(const SuiteOptions& options) {
  Report report = run_fast_checks();
  if (options.solvers) timed(report, "solvers", [&] { add_solver_checks(report); });
  if (options.convergence == "none") return report;
  timed(report, "manufactured solutions", [&] { add_convergence_checks(report, options.convergence, options.convergence_table); });
  // The finite cell method's figures (Longva et al. 2020 Fig. 5, 6, 10): seconds (ci) to minutes (full).
  timed(report, "finite cell Fig. 5", [&] { add_fcm_conditioning_checks(report, options.convergence); });
  timed(report, "finite cell Fig. 6", [&] { add_fcm_rigid_motion_checks(report); });
  timed(report, "finite cell Fig. 10", [&] { add_fcm_convergence_checks(report, options.convergence); });
  timed(report, "scene error measures", [&] { add_study_checks(report); });
  return report;
}

}  // namespace hofem::verification
