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
// 1e3 but scales well still makes the cut. What is skipped is in the JSON with
// the reason.
#include "assembly/dof_map.hpp"
#include "assembly/sparse_matrix.hpp"
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
  /// Newton at the all-combinations sizes: every Krylov method with every
  /// preconditioner (full), or each preconditioner with the method that solved
  /// the projected Neo-Hookean Hessian of that order and size fastest (quick).
  bool newton_every_method = false;
  int keep_at(int level) const { return level < static_cast<int>(keep.size()) ? keep[level] : keep.back(); }
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
std::optional<std::string> setup_failure(const std::string& combo, const std::string& kind);

// ---- runs -------------------------------------------------------------------

/// Starts MPI and hypre (once, untimed) if `solver` will use them, so that their
/// start-up (~0.5 s) is not charged to the first run that does.
void start_runtime_for(const std::string& solver);

/// Runs `work` (returns its time in seconds) once, twice more if it took
/// < 0.2 s and four more if < 20 ms (at ~1e3 unknowns timer and scheduling noise
/// is of the order of the run); returns the median.
template <class Work>
double median_time(Work&& work) {
  std::vector<double> t{work()};
  const int extra = t[0] < 0.02 ? 6 : t[0] < 0.2 ? 2 : 0;
  for (int i = 0; i < extra; ++i) t.push_back(work());
  std::sort(t.begin(), t.end());
  return t[t.size() / 2];
}

/// Reports a run that was not made: error_occurred in the JSON, message "skipped: why".
void skip(benchmark::State& state, const std::string& why);
/// Reports a run that was made but failed: message "failed: why".
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
