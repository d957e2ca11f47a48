// Time to an accurate answer (BM_TimeToError): the manufactured-solution cube of
// `hofem mms` (core/study/manufactured_solution.hpp) solved from scratch
// per repetition, for element order x mesh size x linear solver. What a user of
// `hofem mms` waits for is timed: DOF map, sparsity pattern, load vector,
// Hessian assembly, solver set-up and solve (StaticElasticity's constructor and
// solve()); the mesh generation and the error integration are not. Each
// repetition builds a fresh problem and clears the basis tabulation cache, so
// no pattern, tabulation, transfer or symbolic analysis carries over.
//
// Counters: total_s and its phases (setup_s: DOF map, pattern, load vector;
// assembly_s: Hessians, gradients, energies; solve_s: solver set-up and
// solves), l2_error beside reference_l2_error (the same mesh solved by CHOLMOD,
// or above 100k unknowns by the same iterative solver at rtol 1e-12, as the
// verification study does) and their relative difference l2_vs_reference,
// linear and Newton iterations, peak_mb (resident memory above the start),
// unknowns; for iterative solvers also solver_setup_s, the solver's set-up alone
// (a fresh solver factorising the problem's Hessian at the solution: hierarchy,
// transfers, Galerkin levels, smoothers and the order-1 level for pmg; the faster
// of two, after the first repetition) and solver_setup_us_per_unknown. A direct
// solver's set-up is its factorisation, the bulk of its solve_s. The label names
// the solver actually used ("auto" resolved). The work-precision plot of
// reports/ (scripts/plots/plot_reports.py) reads the medians.
#include "basis/basis_tabulation.hpp"
#include "bench_common.hpp"
#include "study/manufactured_solution.hpp"
#include "linalg/linear_solver.hpp"
#include "solver/solver_factory.hpp"

#include <benchmark/benchmark.h>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <tuple>

namespace hofem::bench {
namespace {

struct TimeToErrorCase {
  std::string problem;  ///< "linear" or "neohookean"
  int order = 2;
  int n = 4;
  std::string solver;   ///< "auto" or a make_linear_solver() name
  bool scaling = false; ///< BM_Scaling: no reference error, no separate set-up timing
};

hofem::MmsCase mms_case(const TimeToErrorCase& c) {
  hofem::MmsCase m;
  m.problem = c.problem;
  m.order = c.order;
  m.n = c.n;
  m.solver = SolverSpec::parse(c.solver);
  return m;
}

// The L2 error of the same mesh solved to the reference accuracy (once per
// mesh, outside the timing; a CHOLMOD case's own error serves the others).
std::map<std::tuple<std::string, int, int>, double>& reference_cache() {
  static std::map<std::tuple<std::string, int, int>, double> cache;
  return cache;
}

void remember_reference(const TimeToErrorCase& c, double l2) {
  reference_cache()[std::make_tuple(c.problem, c.order, c.n)] = l2;
}

double reference_l2_error(const TimeToErrorCase& c, long unknowns, const std::string& iterative_solver) {
  auto& cache = reference_cache();
  const auto key = std::make_tuple(c.problem, c.order, c.n);
  if (auto it = cache.find(key); it != cache.end()) return it->second;
  hofem::MmsCase ref = mms_case(c);
  ref.solver = SolverSpec::parse("cholmod");
  if (unknowns > 100000 && iterative_solver != "cholmod") {
    ref.solver = SolverSpec::parse(iterative_solver);
    ref.algebraic_rtol = 1e-12;
  }
  const hofem::MmsResult r = hofem::run_mms(ref);
  return cache[key] = r.converged ? r.l2_error : std::nan("");
}

// A fresh solver's set-up on the problem's Hessian at its solution (seconds):
// the faster of two fresh solvers (the machines are noisy; the work is the same).
// Iterative solvers only: a direct solver's set-up is its factorisation, the bulk
// of its solve_s already.
double time_solver_setup(StaticElasticity& problem, const std::string& solver) {
  if (solver == "cholmod" || solver == "umfpack" || solver == "eigen-ldlt") return std::nan("");
  SparseMatrix K;
  Eigen::VectorXd g;
  problem.hessian(problem.dofs().restrict(problem.displacement()), g, K, false);
  double best = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 2; ++k) {
    auto s = make_linear_solver(solver);
    s->set_mesh_view({&problem.mesh(), &problem.dofs()});
    const auto t0 = Clock::now();
    if (!s->factorize(K)) return std::nan("");
    best = std::min(best, seconds_since(t0));
  }
  return best;
}

// The solver's set-up is timed in a case's first repetition only and reported
// again by the others: the same Hessian and solver each time, so re-timing it
// would only repeat two set-ups per repetition (8 of the stage's ~120 s at P3
// n = 16 and 12) outside the timed interval.
double solver_setup_once(const TimeToErrorCase& c, StaticElasticity& problem, const std::string& solver) {
  static std::map<std::tuple<std::string, int, int, std::string>, double> timed;
  const auto key = std::make_tuple(c.problem, c.order, c.n, c.solver);
  if (auto it = timed.find(key); it != timed.end()) return it->second;
  return timed[key] = time_solver_setup(problem, solver);
}

// One repetition = one fresh problem, built before the timed loop (mesh, u*,
// body force) and measured after it (errors, the solver's set-up alone): the
// timed interval, over which real_time and cpu_time (the process's, every
// thread) are both taken, is StaticElasticity's constructor and solve().
void BM_TimeToError(benchmark::State& state, const TimeToErrorCase& c) {
  clear_tabulation_cache();
  const hofem::MmsProblem p(mms_case(c));
  PeakMemory memory;
  std::optional<StaticElasticity> problem;
  StaticReport report;
  double total = 0.0;
  for (auto _ : state) {
    const auto t0 = Clock::now();
    problem.emplace(p.mesh, *p.material, p.dirichlet, p.body_force, p.options);
    report = problem->solve();
    total = seconds_since(t0);
  }
  const double peak = memory.extra_mb();
  if (!report.converged) return fail(state, "did not converge: " + report.message);
  const long unknowns = static_cast<long>(problem->dofs().num_free());
  const double l2 = hofem::mms_errors(p.mesh, p.ustar, problem->displacement()).l2;
  double solver_setup = std::nan("");
  if (!c.scaling) {
    solver_setup = solver_setup_once(c, *problem, report.linear_solver);
    if (report.linear_solver == "cholmod") remember_reference(c, l2);  // a direct solve is the reference
  }
  if (c.scaling) {
    const double per_unknown = static_cast<double>(unknowns);
    state.counters["total_s"] = total;
    state.counters["us_per_unknown"] = 1e6 * total / per_unknown;
    state.counters["setup_s"] = report.setup_seconds;
    state.counters["assembly_s"] = report.assembly_seconds;
    state.counters["solve_s"] = report.solve_seconds;
    state.counters["l2_error"] = l2;
    state.counters["linear_iterations"] = report.linear_iterations;
    state.counters["newton_iterations"] = report.newton_iterations;
    state.counters["peak_mb"] = peak;
    state.counters["peak_bytes_per_unknown"] = 1e6 * peak / per_unknown;
    state.counters["unknowns"] = per_unknown;
    state.counters["order"] = c.order;
    state.counters["n"] = c.n;
    state.SetLabel(fmt::format("{}|{}", c.problem, report.linear_solver));
    return;
  }
  const double reference = reference_l2_error(c, unknowns, report.linear_solver);
  state.counters["total_s"] = total;
  state.counters["setup_s"] = report.setup_seconds;
  state.counters["assembly_s"] = report.assembly_seconds;
  state.counters["solve_s"] = report.solve_seconds;
  state.counters["l2_error"] = l2;
  state.counters["reference_l2_error"] = reference;
  state.counters["l2_vs_reference"] = std::abs(l2 / reference - 1.0);
  state.counters["linear_iterations"] = report.linear_iterations;
  state.counters["newton_iterations"] = report.newton_iterations;
  state.counters["peak_mb"] = peak;
  if (std::isfinite(solver_setup)) {  // iterative solvers (no NaN in the JSON)
    state.counters["solver_setup_s"] = solver_setup;
    state.counters["solver_setup_us_per_unknown"] = 1e6 * solver_setup / static_cast<double>(unknowns);
  }
  state.counters["unknowns"] = static_cast<double>(unknowns);
  state.counters["order"] = c.order;
  state.counters["n"] = c.n;
  state.SetLabel(fmt::format("{}|{}", c.problem, report.linear_solver));
}

// The cases: the four targets (linear P3 n = 12, P2 n = 16, P3 n = 16,
// Neo-Hookean P3 n = 8) inside error sequences per order, each with the default
// solver ("auto") and with CHOLMOD (the previous default) where a direct solve
// takes under ~10 s. Three repetitions (CHOLMOD one), one solve each, medians reported.
const bool registered = [] {
  std::vector<TimeToErrorCase> cases;
  // CHOLMOD first: its errors are the references of the auto cases of the same mesh.
  for (int n : {8, 16}) cases.push_back({"linear", 2, n, "cholmod"});
  for (int n : {6, 8, 12}) cases.push_back({"linear", 3, n, "cholmod"});
  for (int n : {8}) cases.push_back({"neohookean", 3, n, "cholmod"});
  for (int n : {4, 8, 16}) cases.push_back({"linear", 1, n, "auto"});
  for (int n : {24}) cases.push_back({"linear", 1, n, "auto"});
  for (int n : {4, 8, 12, 16}) cases.push_back({"linear", 2, n, "auto"});
  for (int n : {4, 6, 8, 12, 16}) cases.push_back({"linear", 3, n, "auto"});
  for (int n : {4, 6, 8}) cases.push_back({"neohookean", 3, n, "auto"});
  for (const TimeToErrorCase& c : cases)
    benchmark::RegisterBenchmark(fmt::format("BM_TimeToError/{}/p{}/n{}/{}", c.problem, c.order, c.n, c.solver).c_str(),
                                 [c](benchmark::State& s) { BM_TimeToError(s, c); })
        ->Iterations(1)
        // CHOLMOD, the reference of the comparison, once (its 5-12 s solves were
        // ~60 s of the main job in three repetitions; a direct solve varies less).
        ->Repetitions(c.solver == "cholmod" ? 1 : 3)
        ->MeasureProcessCPUTime()
        ->Unit(benchmark::kSecond);
  // BM_Scaling (scripts/scaling, opt-in: HOFEM_BENCH_SCALING=1): the linear cube
  // on the default solver from ~1e5 to ~2e6 unknowns, one solve per size, for
  // time, iterations and peak memory per unknown (P3 to n = 24, 1.07 M
  // unknowns; P2 to n = 45, 2.1 M). Minutes and ~10 GB: not in the main job.
  if (std::getenv("HOFEM_BENCH_SCALING")) {
    std::vector<TimeToErrorCase> scaling;
    for (int n : {8, 12, 16, 20, 24}) scaling.push_back({"linear", 3, n, "auto", true});
    for (int n : {16, 24, 32, 40, 45}) scaling.push_back({"linear", 2, n, "auto", true});
    for (const TimeToErrorCase& c : scaling)
      benchmark::RegisterBenchmark(fmt::format("BM_Scaling/{}/p{}/n{}/{}", c.problem, c.order, c.n, c.solver).c_str(),
                                   [c](benchmark::State& s) { BM_TimeToError(s, c); })
          ->Iterations(1)
          ->MeasureProcessCPUTime()
          ->Unit(benchmark::kSecond);
  }
  return true;
}();

}  // namespace
}  // namespace hofem::bench
