// The Neo-Hookean manufactured solution solved by the static solver (Newton with
// load stepping, problem/static_elasticity.hpp) with every linear solver of
// linear_solver_names() and a fixed linear tolerance 1e-8 for the iterative ones
// ("/fixed"; quick preset: each preconditioner with the Krylov method that
// solved the projected Neo-Hookean Hessian of that order and size fastest in the
// linear sweep, which runs before); for the fastest fixed-tolerance combinations of each size also with
// Eisenstat-Walker forcing terms ("/ew", inexact Newton). Orders 1-3 on
// tetrahedra, ~1e3 unknowns and, for the 3 components predicted fastest, ~1e4
// (quick) / up to ~1e5 (full). (Every method x preconditioner meets the Newton
// Hessians in the hessian-nh* linear sweeps; here the point is the whole solve.)
//
// Time: the whole static solve (set-up of the problem, all Newton iterations),
// one per repetition (Preset::repetitions, bench_common.hpp); cpu_time is the
// process's CPU time (every thread) over the same interval.
// Counters: newton_iterations, linear_iterations, load_steps, assembly_s (energy,
// gradient and Hessian assembly), solve_s (everything else in the Newton loop:
// factorisations / preconditioner set-ups and solves), assembly_share =
// assembly_s / (assembly_s + solve_s) — the assembly vs solve share of a Newton
// step —, l2_error / h1_error against u*, peak_MB / extra_MB.
#include "bench_common.hpp"

#include "study/manufactured_solution.hpp"
#include "problem/static_elasticity.hpp"
#include "linalg/linear_solver.hpp"
#include "solver/solver_factory.hpp"

#include <benchmark/benchmark.h>

#include <exception>
#include <memory>
#include <optional>
#include <string>

namespace hofem::bench {
namespace {

bool is_direct(const std::string& name) { return SolverSpec::parse(name).is_direct(); }

struct NewtonCase {
  hofem::MmsCase mms;
  int level = 0;
  std::string solver;
  bool eisenstat_walker = false;
  std::string tag() const {
    return "mms-neohookean/tet/p" + std::to_string(mms.order) + "/n" + std::to_string(mms.n);
  }
  std::string series() const { return "mms-neohookean|tet|p" + std::to_string(mms.order); }
  std::string combo() const { return solver + (is_direct(solver) ? "" : eisenstat_walker ? "/ew" : "/fixed"); }
};

// The problem of the last case (mesh, material, u*), rebuilt when the case changes.
const hofem::MmsProblem& mms_problem(const hofem::MmsCase& c) {
  static std::unique_ptr<hofem::MmsProblem> problem;
  static std::string key;
  const std::string k = std::to_string(c.order) + "/" + std::to_string(c.n);
  if (!problem || key != k) {
    problem.reset();
    problem = std::make_unique<hofem::MmsProblem>(c);
    key = k;
  }
  return *problem;
}

struct NewtonSample {
  StaticReport report;
  Eigen::VectorXd u;
  double seconds = 0.0;
  std::string error;
};

NewtonSample solve_once(const hofem::MmsProblem& p, const NewtonCase& c) {
  NewtonSample s;
  StaticOptions options = p.options;
  options.solver = SolverSpec::parse(c.solver);
  options.newton.eisenstat_walker = c.eisenstat_walker;
  const auto t0 = Clock::now();
  try {
    StaticElasticity problem(p.mesh, *p.material, p.dirichlet, p.body_force, options);
    s.report = problem.solve();
    s.u = problem.displacement();
  } catch (const std::exception& e) {
    s.error = e.what();
  }
  s.seconds = seconds_since(t0);
  return s;
}

// Why a configuration is not run, decided at its first repetition: the sweep's
// policy, a solver that does not exist for the order (order_skip_reason), a set-up failure of its preconditioner or direct solver on this
// element kind in the linear sweep, (quick preset) a Krylov method that was not
// the fastest for its preconditioner on the projected Hessians, or a solver
// this build cannot make.
std::optional<std::string> newton_skip_reason(const NewtonCase& c) {
  const double unknowns = static_cast<double>(free_unknowns("mms-neohookean", CellType::Tetrahedron, c.mms.order, c.mms.n));
  if (auto why = sweep_skip_reason(c.series(), c.level, c.combo(), unknowns, is_direct(c.solver), 3)) return why;
  if (auto why = order_skip_reason(c.solver, c.mms.order)) return why;
  if (auto why = setup_failure(c.solver, "tet/p" + std::to_string(c.mms.order))) return why;
  if (!preset().newton_every_method && !is_direct(c.solver) && preset().keep_at(c.level) == 0 && !c.eisenstat_walker) {
    const std::string hessians = "hessian-nh-psd|tet|p" + std::to_string(c.mms.order);
    const auto best = fastest_of_component(hessians, c.level, c.solver);
    if (best && *best != c.solver)
      return *best + " solved the projected Neo-Hookean Hessian of this order and size fastest of the '" +
             c.solver.substr(c.solver.find('+') + 1) + "' combinations (preset " + preset().name + ")";
  }
  try {
    start_runtime_for(c.solver);
    make_linear_solver(c.solver);
  } catch (const std::exception& e) {
    return std::string("not available: ") + e.what();
  }
  return std::nullopt;
}

// Counters, the policy's record and the verdict of one repetition.
void report_newton(benchmark::State& state, const NewtonCase& c, const hofem::MmsProblem& p, const NewtonSample& s,
                   const PeakMemory& memory, CaseProgress& progress) {
  const StaticReport& r = s.report;
  state.counters["newton_iterations"] = r.newton_iterations;
  state.counters["linear_iterations"] = r.linear_iterations;
  state.counters["load_steps"] = r.load_steps;
  state.counters["setup_s"] = r.setup_seconds;
  state.counters["assembly_s"] = r.assembly_seconds;
  state.counters["solve_s"] = r.solve_seconds;
  state.counters["assembly_share"] = r.assembly_seconds / std::max(1e-300, r.assembly_seconds + r.solve_seconds);
  state.counters["factorizations"] = r.factorizations;
  state.counters["peak_MB"] = memory.peak_mb();
  state.counters["extra_MB"] = memory.extra_mb();
  if (!r.steps.empty() && r.steps.back().force_scale > 0.0)
    state.counters["rel_residual"] = r.steps.back().final_residual / r.steps.back().force_scale;
  const bool ok = s.error.empty() && r.converged;
  if (ok) {
    const auto err = hofem::mms_errors(p.mesh, p.ustar, s.u);
    state.counters["l2_error"] = err.l2;
    state.counters["h1_error"] = err.h1;
  }
  progress.add(s.seconds, memory.extra_mb(), ok);
  const double unknowns = static_cast<double>(free_unknowns("mms-neohookean", CellType::Tetrahedron, c.mms.order, c.mms.n));
  record_run(c.series(), c.level, c.combo(), {unknowns, progress.median(), progress.extra_mb, progress.all_ok});
  if (!ok) fail(state, (s.error.empty() ? r.message : s.error) + " (after " + std::to_string(s.seconds) + " s)");
}

void run_newton(benchmark::State& state, const NewtonCase& c, CaseProgress& progress) {
  state.counters["unknowns"] = static_cast<double>(free_unknowns("mms-neohookean", CellType::Tetrahedron, c.mms.order, c.mms.n));
  state.counters["order"] = c.mms.order;
  state.counters["level"] = c.level;
  state.counters["eisenstat_walker"] = c.eisenstat_walker;
  state.SetLabel(c.tag() + " " + c.combo());
  if (!progress.decided) {
    progress.skip_reason = newton_skip_reason(c);
    progress.decided = true;
  }
  if (progress.skip_reason) return skip(state, *progress.skip_reason);
  const hofem::MmsProblem& p = mms_problem(c.mms);
  const PeakMemory memory;
  NewtonSample s;
  for (auto _ : state) s = solve_once(p, c);  // the timed interval
  report_newton(state, c, p, s, memory, progress);
}

}  // namespace

void register_newton_sweep() {
  const int top = preset().max_level - 1;
  for (int order = 1; order <= 3; ++order)
    for (int level = 0; level <= top; ++level)
      for (bool ew : {false, true})  // the Eisenstat-Walker variants after (and ranked on) the fixed-tolerance runs
        for (const std::string& solver : linear_solver_names()) {
          if (ew && is_direct(solver)) continue;  // Eisenstat-Walker changes nothing for a direct solver
          NewtonCase c;
          c.mms.problem = "neohookean";
          c.mms.solver = SolverSpec::parse("cholmod");  // MmsProblem's options at Newton rtol 1e-10, not auto's
          c.mms.order = order;
          c.mms.n = cubes_for_level("mms-neohookean", CellType::Tetrahedron, order, level);
          c.level = level;
          c.solver = solver;
          c.eisenstat_walker = ew;
          auto progress = std::make_shared<CaseProgress>();
          benchmark::RegisterBenchmark(("BM_NewtonSolve/" + c.tag() + "/" + c.combo()).c_str(),
                                       [c, progress](benchmark::State& state) { run_newton(state, c, *progress); })
              ->Iterations(1)
              ->Repetitions(preset().repetitions_at(level))
              ->MeasureProcessCPUTime()
              ->Unit(benchmark::kMillisecond);
        }
}

}  // namespace hofem::bench
