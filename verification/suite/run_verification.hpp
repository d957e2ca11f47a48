#pragma once
// The verification suite as a table of check families: each adds the rows of
// a few groups ("quadrature.exactness", "mms.rate_h1", ...) to a Report. The
// table says which groups a family writes, so `hofem verify --group P` runs
// only the families that can write a group starting with P; ctest runs each
// family as its own test (verify.<id>, labelled fast, mpi or convergence).
#include "report.hpp"
#include "study/convergence_table.hpp"

#include <functional>
#include <string>
#include <vector>

namespace hofem::verification {

struct SuiteOptions {
  /// Manufactured-solution convergence study: "none", "ci" or "full".
  std::string convergence = "ci";
  /// Run only the families that can write a group starting with this prefix
  /// (empty: all). The report still holds every row the run families wrote.
  std::string group{};
  /// Progress lines on stderr (provenance/progress.hpp) while the families run.
  bool progress = false;
  /// If set, receives one row per run of the convergence study (the tidy
  /// table `hofem verify` writes beside its report).
  ConvergenceTable* convergence_table = nullptr;
};

struct CheckFamily {
  std::string id;                   ///< short name: `verify --list`, ctest verify.<id>
  std::string title;                ///< the "timing" measurement's name
  std::vector<std::string> groups;  ///< prefixes of the groups its rows carry
  std::string label;                ///< ctest label: "fast", "mpi" (starts MPI) or "convergence"
  bool convergence = false;         ///< skipped with convergence "none"
  /// Wall seconds measured on the 2-core reference machine with the ci and the
  /// full preset: the progress lines' estimate of what remains, nothing else.
  double ci_seconds = 1.0, full_seconds = 1.0;
  /// Adds the family's rows; reads the preset (and the convergence table) from the options.
  std::function<void(Report&, const SuiteOptions&)> add;
};

/// Every family, in the order the suite runs them.
const std::vector<CheckFamily>& check_families();

/// Whether `family` can write a group starting with `prefix` (or the prefix
/// starts with one of its groups): "embedded" selects every finite-cell family,
/// "mms.rate_h1" the manufactured solutions.
bool family_selected(const CheckFamily& family, const std::string& prefix);

/// The families options.group and options.convergence select, in running order.
std::vector<const CheckFamily*> selected_families(const SuiteOptions& options);
/// What a selection of none is told: the group prefixes there are.
std::string no_families_message(const SuiteOptions& options);

/// Fast checks: quadrature, bases, materials, elements, patch tests, dynamics,
/// embedded quadrature and loads, partition quality (seconds).
Report run_fast_checks();

/// The selected families (all by default), each timed into the group "timing".
/// Throws std::invalid_argument if none is selected (no_families_message).
Report run_checks(const SuiteOptions& options = {});

}  // namespace hofem::verification
