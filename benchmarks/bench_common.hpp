#pragma once
// Shared pieces of the solver sweep (bench_solvers*.cpp) and the bandwidth
// benchmarks (bench_bandwidth.cpp): the preset, problem sizes, the cache of
// assembled linear systems, peak-memory and bandwidth-floor measurement, the
// record of finished runs that later sizes are predicted from, and the residual
// histories written to HOFEM_BENCH_HISTORY_OUT.
//
// Presets (HOFEM_BENCH_PRESET): "quick" (default, part of scripts/run) runs every
// solver x preconditioner at ~1e3 unknowns, then at ~1e4 / ~1e5 the 6 / 3
// preconditioners (or direct solvers) predicted fastest there, each with its
// predicted-fastest Krylov method, plus the multilevel preconditioners (amg,
// pmg) whenever they solved the size below; 10 s budget per run; "full"
// (scripts/bench-full) runs every combination up to ~1e5 and the 4 predicted
// fastest at ~1e6, 120 s per run.
// Why: every combination at every size is hours on these 2-core machines (one
// unpreconditioned or single-level solve at 1e5 takes seconds to minutes); the
// ~1e3 runs show what works at all (convergence, breakdowns, set-up failures),
// and the larger sizes spend the time on different methods that can be fastest
// there. Predictions extrapolate a combination's own smaller runs (growth
// exponent from the two nearest sizes), so a multilevel method that is slow at
// 1e3 but scales well still makes the cut. What is skipped is not in the JSON
// of the results: its names and reasons go to HOFEM_BENCH_SKIPS_OUT
// (bench_skip_reporter.hpp).
//
// Repetitions: each configuration is one benchmark with Preset::repetitions at
// its size level, each repetition one run (set-up + solve) and an entry of its
// own, so Google Benchmark computes median / mean / stddev / cv and
// tools/compare.py can run its Mann-Whitney U test on two files. Quick: 5 at
// ~1e3, where runs take milliseconds and the noise is of their order (with 5
// against 5 an exact two-sided U test can reach p = 0.008; with 3 against 3 it
// never goes below 0.1, so 3 would not do), 1 at ~1e4 and above, whose runs
// take 0.1-6 s (reports/solver_benchmarks.json of 2026-12-02: one run of each
// configuration the quick sweep made is 48 s, 42 s of it at those sizes; two
// repetitions there would add ~42 s to the main job's 113 s sweep and still
// leave the U test unable to go below p = 0.33). The full preset repeats the
// same way.
#include "assembly/dof_map.hpp"
#include "linalg/sparse_matrix.hpp"
#include "study/manufactured_solution.hpp"
#include "mesh/mesh.hpp"
#include "quadrature/cell_type.hpp"

#include <Eigen/Core>
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace hofem::bench {

using Clock = std::chrono::steady_clock;
inline double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// ---- preset and sizes -------------------------------------------------------

struct Preset {
  std::string name;          ///< "quick" or "full"
  int max_level = 2;         ///< largest size level run at all (level k ~ 10^(k+3) unknowns)
  /// Per level: 0 = every combination; k > 0 = the k preconditioners / direct
  /// solvers predicted fastest there, each with its predicted-fastest method.
  std::vector<int> keep{0, 6, 3};
  double time_budget = 10.0; ///< seconds: runs predicted to take longer are skipped
  /// Per level: repetitions of each configuration (the last entry for the levels beyond).
  std::vector<int> repetitions{5, 1};
  /// Newton at the all-combinations sizes: every Krylov method with every
  /// preconditioner (full), or each preconditioner with the method that solved
  /// the projected Neo-Hookean Hessian of that order and size fastest (quick).
  bool newton_every_method = false;
  int keep_at(int level) const { return level < static_cast<int>(keep.size()) ? keep[level] : keep.back(); }
  int repetitions_at(int level) const {
    return level < static_cast<int>(repetitions.size()) ? repetitions[level] : repetitions.back();
  }
};
const Preset& preset();

/// Target unknowns of a size level: 1e3, 1e4, 1e5, 1e6.
double level_target(int level);
/// The deformed-Hessian problems' domain: a bar [0, 4] x [0, 1] x [0, 1] (4n x n x n
/// cubes) with its ends clamped; the others are the unit cube (n^3 cubes) with the
/// whole boundary clamped.
constexpr double kBarLength = 4.0;
bool is_bar_problem(const std::string& problem);
/// Free unknowns of a problem's mesh with n cubes across.
long free_unknowns(const std::string& problem, CellType cell, int order, int n);
/// Cubes across whose free unknowns are nearest (in log) to the level's target.
int cubes_for_level(const std::string& problem, CellType cell, int order, int level);
const char* cell_tag(CellType cell, int order);  ///< "tet", "hex8", "hex20"

// ---- linear systems ---------------------------------------------------------

/// "mms-linear": K u = f of the linear manufactured solution (u = u* on the
/// boundary, eliminated); "hessian-nh": the unprojected Neo-Hookean Hessian of a
/// bar compressed 35 % between its clamped ends, past its buckling loads
/// (indefinite), b = -g; "hessian-nh-psd": the same with per-point PSD projection.
struct SystemKey {
  std::string problem;
  CellType cell = CellType::Tetrahedron;
  int order = 1;
  int n = 4;
  bool operator<(const SystemKey& o) const;
  std::string tag() const;  ///< "mms-linear/tet/p2/n8"
  long unknowns() const { return free_unknowns(problem, cell, order, n); }
};

struct LinearSystem {
  SystemKey key;
  std::unique_ptr<hofem::MmsProblem> mms;  ///< mms-linear: mesh, material, u*
  Mesh bar;                 ///< hessian-nh*: the bar's mesh
  DofMap dofs;
  SparseMatrix K;
  Eigen::VectorXd b;
  Eigen::VectorXd u_fixed;  ///< displacement of every DOF with the free ones zero (Dirichlet values)
  bool has_exact = false;   ///< u* known: L2 errors are measured
  bool positive_definite = true;  ///< by a CHOLMOD factorisation when built (hessian-nh only)
  std::string definiteness_note;
  double assembly_seconds = 0.0;  ///< pattern, K and b (once per system; not in the solver timings)
  const Mesh& mesh() const { return mms ? mms->mesh : bar; }
};

/// The system of a key, built on first use and kept (a few at a time; the least
/// recently used is dropped when more than ~2.5e6 unknowns are cached).
const LinearSystem& linear_system(const SystemKey& key);

/// L2 / H1 errors of a free-DOF solution x of an MMS system (NaN without u*).
hofem::MmsErrors solution_errors(const LinearSystem& s, const Eigen::VectorXd& x);

// ---- measurement ------------------------------------------------------------

/// Peak resident memory of this process: reset() writes 5 to /proc/self/clear_refs
/// (resets VmHWM to the current RSS), peak_mb() reads VmHWM. Falls back to
/// getrusage's lifetime maximum (reset impossible; `peak_resettable` is 0) if the
/// file is not writable.
struct PeakMemory {
  PeakMemory();  ///< resets the peak and records the current RSS
  double peak_mb() const;
  double extra_mb() const { return peak_mb() - start_mb; }  ///< above the RSS at construction
  double start_mb = 0.0;
  bool resettable = false;
};
double memory_available_mb();

/// STREAM-like triad a = b + s c on three 64 MiB arrays (2x the L3 of these
/// machines each), 1 thread, best of 10 passes, measured on first call and kept:
/// the bandwidth floor every ratio of this run refers to. Bytes: 24 per element
/// (two loads, one store; write-allocate not counted, as STREAM does).
double triad_bytes_per_second();
/// The same triad measured now, best of `passes` (for a floor next to a kernel
/// on a machine whose load drifts).
double measure_triad(int passes);
/// The triad on every OpenMP thread, measured now, best of `passes`: the floor of
/// kernels that themselves run on every thread.
double measure_triad_all_threads(int passes);
/// Double-precision FLOP/s of independent FMA chains in the widest vectors the
/// build targets (AVX-512: 8 doubles, AVX2: 4, else scalar), on `threads` OpenMP
/// threads, measured now (best of 3): the compute peak beside which kernels'
/// executed FLOPs are quoted.
double measure_fma_peak(int threads);

// ---- records of finished runs (prediction, ranking) -------------------------

struct RunRecord {
  double unknowns = 0.0;
  double seconds = 0.0;   ///< set-up + solve
  double extra_mb = 0.0;  ///< peak memory above the start
  bool ok = false;        ///< converged / solved
};
/// series: problem|cell|order (the thing sizes vary over); combo: solver name.
void record_run(const std::string& series, int level, const std::string& combo, const RunRecord& r);
/// Why a run of `combo` at `level` should not be run, or nothing: a failure at a
/// smaller level, its preconditioner (or direct solver) having taken longer than
/// the budget at this size or below in any series, (above the all-combinations
/// levels) not being among the `keep_fastest` by predicted time, a predicted time
/// above the budget, or a direct factor predicted beyond half the free memory.
/// keep_cap > 0 lowers the number of components kept (the Newton sweep: 3).
std::optional<std::string> sweep_skip_reason(const std::string& series, int level, const std::string& combo,
                                             double unknowns, bool direct, int keep_cap = 0);

/// The fastest solved combination of `combo`'s component (its preconditioner, or
/// the solver itself) in `series` at `level`, if any ran.
std::optional<std::string> fastest_of_component(const std::string& series, int level, const std::string& combo);

/// Set-up failures of a preconditioner or direct solver ("pmg needs element order
/// >= 2") by element kind (cell_tag + order), recorded by the linear sweep and
/// looked up by the Newton sweep, which would otherwise only see Newton fail.
void record_setup_failure(const std::string& combo, const std::string& kind, const std::string& why);

/// A configuration that does not exist for this element order: p-multigrid
/// coarsens to order 1 (Hex8 / Tet4), so on an order-1 mesh there is nothing to
/// coarsen and its set-up refuses it every time (not a failure of the method).
/// Used by the linear and the Newton sweep alike.
std::optional<std::string> order_skip_reason(const std::string& combo, int order);
std::optional<std::string> setup_failure(const std::string& combo, const std::string& kind);

// ---- runs -------------------------------------------------------------------

/// Starts MPI and hypre (once, untimed) if `solver` will use them, so that their
/// start-up (~0.5 s) is not charged to the first run that does.
void start_runtime_for(const std::string& solver);

/// What one configuration of the sweep carries from one repetition to the next
/// (each repetition is a fresh call of its benchmark function): whether it is
/// run at all, decided once at the first repetition (otherwise a first
/// repetition over the budget would skip the others, bench_policy.cpp), and what
/// the repetitions made so far measured, for the policy's record of the run.
struct CaseProgress {
  bool decided = false;
  std::optional<std::string> skip_reason;
  std::vector<double> seconds;  ///< set-up + solve of each repetition made
  double extra_mb = 0.0;        ///< the largest of their peak memories above the start
  bool all_ok = true;           ///< every repetition solved
  void add(double s, double mb, bool ok) {
    seconds.push_back(s);
    extra_mb = std::max(extra_mb, mb);
    all_ok = all_ok && ok;
  }
  double median() const {
    std::vector<double> t = seconds;
    std::sort(t.begin(), t.end());
    return t.empty() ? 0.0 : t[t.size() / 2];
  }
};

/// A configuration not run on purpose: the run is reported as skipped (message
/// "skipped: why"), which keeps it out of the results (bench_skip_reporter.hpp).
void skip(benchmark::State& state, const std::string& why);
/// A run that was made but failed: an error in the results, message "failed: why".
void fail(benchmark::State& state, const std::string& why);

/// Residual histories (relative residual per iteration), kept when
/// HOFEM_BENCH_HISTORY_OUT names a file and written there as JSON at exit.
bool histories_wanted();
void add_history(const std::string& benchmark, const std::string& problem, const std::string& solver, double unknowns,
                 const std::vector<double>& history);

// Registration (called once, in this order, from bench_common.cpp).
void register_linear_sweep();   // bench_solvers.cpp: mms-linear
void register_bandwidth();      // bench_bandwidth.cpp
void register_hessian_sweep();  // bench_solvers.cpp: hessian-nh, hessian-nh-psd
void register_newton_sweep();   // bench_solvers_newton.cpp

}  // namespace hofem::bench
