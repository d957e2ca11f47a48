#include "run_verification.hpp"

#include "basis_checks.hpp"
#include "convergence_checks.hpp"
#include "dynamics_checks.hpp"
#include "element_checks.hpp"
#include "embedded_checks.hpp"
#include "fcm_conditioning_checks.hpp"
#include "fcm_convergence_checks.hpp"
#include "fcm_load_checks.hpp"
#include "fcm_rigid_motion_checks.hpp"
#include "fcm_setup_checks.hpp"
#include "material_checks.hpp"
#include "partition_checks.hpp"
#include "provenance/progress.hpp"
#include "quadrature_checks.hpp"
#include "solver_agreement_checks.hpp"
#include "solver_checks.hpp"
#include "study_checks.hpp"

#include <fmt/format.h>

#include <chrono>
#include <optional>
#include <stdexcept>

namespace hofem::verification {

namespace {

// A family whose checks take no preset.
template <void (*Add)(Report&)>
void plain(Report& r, const SuiteOptions&) {
  Add(r);
}

std::vector<CheckFamily> make_families() {
  // Seconds (ci, full) from reports/verification.json's "timing" group on the
  // 2-core reference machine; only the progress estimate reads them.
  return {
      {"quadrature", "quadrature", {"quadrature."}, "fast", false, 2.0, 2.0, plain<add_quadrature_checks>},
      {"basis", "basis", {"basis."}, "fast", false, 0.7, 0.7, plain<add_basis_checks>},
      {"material", "material", {"material."}, "fast", false, 0.1, 0.1, plain<add_material_checks>},
      {"element", "element", {"element."}, "fast", false, 0.1, 0.1, plain<add_element_checks>},
      {"patch", "patch", {"patch."}, "fast", false, 0.2, 0.2, plain<add_patch_checks>},
      {"dynamics", "dynamics", {"dynamics."}, "fast", false, 0.5, 0.5, plain<add_dynamics_checks>},
      {"fig4", "embedded quadrature (Fig. 4)", {"embedded.fig4"}, "fast", false, 3.2, 3.2,
       plain<add_embedded_quadrature_checks>},
      {"loads", "embedded loads", {"embedded.loads"}, "fast", false, 1.8, 1.8, plain<add_fcm_load_checks>},
      {"setup", "finite cell set-up", {"embedded.setup"}, "fast", false, 3.0, 3.0, plain<add_fcm_setup_checks>},
      {"partition", "partition", {"partition."}, "fast", false, 0.1, 0.1, plain<add_partition_checks>},
      {"solvers", "solvers", {"solvers."}, "mpi", false, 8.8, 8.8, plain<add_solver_checks>},
      {"mms", "manufactured solutions", {"mms."}, "convergence", true, 60.0, 82.0,
       [](Report& r, const SuiteOptions& o) { add_convergence_checks(r, o.convergence, o.convergence_table); }},
      // The finite cell method's figures (Longva et al. 2020 Fig. 5, 6, 10): seconds (ci) to minutes (full).
      {"fig5", "finite cell Fig. 5", {"embedded.fig5"}, "convergence", true, 10.0, 24.0,
       [](Report& r, const SuiteOptions& o) { add_fcm_conditioning_checks(r, o.convergence); }},
      {"fig6", "finite cell Fig. 6", {"embedded.fig6"}, "convergence", true, 0.4, 0.4,
       plain<add_fcm_rigid_motion_checks>},
      {"fig10", "finite cell Fig. 10", {"embedded.fig10"}, "convergence", true, 20.0, 53.0,
       [](Report& r, const SuiteOptions& o) { add_fcm_convergence_checks(r, o.convergence); }},
      {"study", "scene error measures", {"study"}, "convergence", true, 12.0, 12.0, plain<add_study_checks>},
      {"agreement", "iterative vs direct", {"agreement.iterative_direct"}, "convergence", true, 20.0, 20.0,
       plain<add_solver_agreement_checks>},
  };
}

// Runs one family and records its wall time as a measurement of the group
// "timing" (the main job's budget is accounted per family: DEVELOPERS.md).
void run_timed(Report& report, const CheckFamily& f, const SuiteOptions& options) {
  const auto t0 = std::chrono::steady_clock::now();
  f.add(report, options);
  report.measure("timing", f.title, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(),
                 "wall seconds of this family of checks");
}

}  // namespace

const std::vector<CheckFamily>& check_families() {
  static const std::vector<CheckFamily> families = make_families();
  return families;
}

bool family_selected(const CheckFamily& family, const std::string& prefix) {
  if (prefix.empty()) return true;
  for (const std::string& g : family.groups)
    if (g.starts_with(prefix) || prefix.starts_with(g)) return true;
  return false;
}

Report run_fast_checks() {
  Report report;
  for (const CheckFamily& f : check_families())
    if (f.label == "fast") run_timed(report, f, SuiteOptions{.convergence = "none"});
  return report;
}

std::vector<const CheckFamily*> selected_families(const SuiteOptions& options) {
  std::vector<const CheckFamily*> chosen;
  for (const CheckFamily& f : check_families())
    if (family_selected(f, options.group) && !(f.convergence && options.convergence == "none")) chosen.push_back(&f);
  return chosen;
}

std::string no_families_message(const SuiteOptions& options) {
  std::string groups;
  for (const CheckFamily& f : check_families())
    for (const std::string& g : f.groups) groups += (groups.empty() ? "" : ", ") + g;
  return fmt::format("--group '{}' selects no checks{} (groups start with: {})", options.group,
                     options.convergence == "none" ? " with --convergence none" : "", groups);
}

Report run_checks(const SuiteOptions& options) {
  const std::vector<const CheckFamily*> chosen = selected_families(options);
  if (chosen.empty()) throw std::invalid_argument(no_families_message(options));
  const auto nominal = [&](const CheckFamily& f) { return options.convergence == "full" ? f.full_seconds : f.ci_seconds; };
  double total = 0.0;
  for (const CheckFamily* f : chosen) total += nominal(*f);
  std::optional<ProgressLog> progress;
  if (options.progress) progress.emplace("verify");
  Report report;
  double done = 0.0;
  for (std::size_t k = 0; k < chosen.size(); ++k) {
    const CheckFamily& f = *chosen[k];
    if (progress) progress->stage(fmt::format("[{}/{}] {}", k + 1, chosen.size(), f.title), done / total);
    run_timed(report, f, options);
    done += nominal(f);
  }
  if (progress) progress->done(fmt::format("{} checks, {} failed", report.rows().size(), report.failures()));
  return report;
}

}  // namespace hofem::verification
