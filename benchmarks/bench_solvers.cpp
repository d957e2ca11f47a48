// The linear-solver sweep: every name of linear_solver_names()
// (direct solvers, hypre's PCG, and <cg|cr|minres|gmres>+<every preconditioner>)
// on
//   - "mms-linear": the linear manufactured solution on the unit cube (one solve
//     is the whole solution, so its L2 error against u* is measured),
//   - "hessian-nh": the unprojected Neo-Hookean Hessian of a bar compressed past
//     its buckling loads (indefinite: CG, hypre PCG, CHOLMOD and Eigen LDL^T are
//     skipped with the reason; CR, MINRES, GMRES and UMFPACK run), and
//     "hessian-nh-psd", the same with per-point PSD projection (SPD),
// for element orders 1-3 (Tet4/10/20; Hex8/Hex20 on the MMS at the smaller sizes)
// and sizes ~1e3 ... 1e5 (quick) / 1e6 (full) unknowns.
//
// One benchmark = one (system, solver), repeated Preset::repetitions times at
// its size (bench_common.hpp). The system is assembled once (cached) and the
// solver built before the timed loop; the timed interval (real_time and, over
// the same interval, cpu_time: the process's CPU time, every thread) is set-up
// (analyze + factorize: symbolic and numeric factorisation, or preconditioner
// set-up) plus solve, nothing else. Our Krylov methods stop at 3000
// iterations (relative residual 1e-8, the LinearSolver default). Counters:
// setup_s, solve_s, iterations, rel_residual (||b - A x|| / ||b|| computed
// here), peak_MB / extra_MB (resident memory peak during the run / above the
// resident size before it), l2_error / h1_error against u*. Configurations not
// run are skipped with the reason (skip(): absent from the results, listed in
// HOFEM_BENCH_SKIPS_OUT); runs made that did not solve, set-up failures
// included, are errors "failed: <why>" (see bench_common.hpp for the rules).
#include "bench_common.hpp"

#include "linalg/krylov.hpp"
#include "linalg/linear_solver.hpp"
#include "solver/solver_spec.hpp"
#include "solver/solver_factory.hpp"

#include <benchmark/benchmark.h>

#include <cmath>
#include <exception>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace hofem::bench {
namespace {

constexpr double kRelativeTolerance = 1e-8;  // iterative solvers (the LinearSolver default)
constexpr int kHistoryLevels = 1;            // residual histories are kept up to ~1e4 unknowns

// The solver of a name, as make_linear_solver() makes it, except that our Krylov
// methods stop after kMaxIterations (their default is 5000): a combination that
// needs more is reported as failed instead of taking minutes.
constexpr int kMaxIterations = 3000;
std::unique_ptr<LinearSolver> make_solver(const std::string& name) {
  SolverSpec spec = SolverSpec::parse(name);
  spec.krylov.rtol = kRelativeTolerance;
  spec.krylov.max_iterations = kMaxIterations;
  return make_linear_solver(spec);
}

bool is_direct(const std::string& name) { return SolverSpec::parse(name).is_direct(); }

// Methods that need a positive-definite matrix: CG (ours and hypre's) and
// Cholesky; Eigen's LDL^T works on indefinite matrices but, by the
// LinearSolver contract, reports them as not positive definite.
bool needs_spd(const std::string& name) {
  const std::optional<SolverMethod> m = SolverSpec::parse(name).method;
  return m == SolverMethod::Cholmod || m == SolverMethod::EigenLdlt || m == SolverMethod::HyprePcg ||
         m == SolverMethod::Cg;
}

struct Sample {
  bool set_up = false, solved = false;
  double setup_s = 0.0, solve_s = 0.0;
  int iterations = 0;
  Eigen::VectorXd x;
  std::vector<double> history;
  std::string message;
  double total() const { return setup_s + solve_s; }
};

Sample solve_once(const LinearSystem& sys, LinearSolver& solver) {
  Sample s;
  solver.set_mesh_view({&sys.mesh(), &sys.dofs});
  solver.set_relative_tolerance(kRelativeTolerance);
  auto* krylov = dynamic_cast<KrylovSolver*>(&solver);
  const auto t0 = Clock::now();
  try {
    solver.analyze(sys.K);
    s.set_up = solver.factorize(sys.K);
    if (!s.set_up)
      s.message = krylov ? krylov->preconditioner().last_error() : "the factorisation reports the matrix not positive definite";
  } catch (const std::exception& e) {
    s.message = e.what();
  }
  s.setup_s = seconds_since(t0);
  if (!s.set_up) return s;
  const auto t1 = Clock::now();
  try {
    solver.solve(sys.b, s.x);
    s.solved = true;
  } catch (const std::exception& e) {
    s.message = e.what();
  }
  s.solve_s = seconds_since(t1);
  s.iterations = solver.last_iterations();
  if (krylov) s.history = krylov->last_result().history;
  return s;
}

struct LinearCase {
  SystemKey key;
  int level = 0;
  std::string solver;
  std::string series() const { return key.problem + "|" + cell_tag(key.cell, key.order) + "|p" + std::to_string(key.order); }
};

std::string kind_tag(const SystemKey& key) { return cell_tag(key.cell, key.order) + std::string("/p") + std::to_string(key.order); }

// Why a configuration is not run, decided at its first repetition: the sweep's
// policy, a solver this build cannot make, or a method that needs a
// positive-definite matrix on an indefinite one. Builds the system (untimed).
std::optional<std::string> linear_skip_reason(const LinearCase& c) {
  const double unknowns = static_cast<double>(c.key.unknowns());
  if (auto why = sweep_skip_reason(c.series(), c.level, c.solver, unknowns, is_direct(c.solver))) return why;
  try {
    start_runtime_for(c.solver);
    make_solver(c.solver);
  } catch (const std::exception& e) {
    return std::string("not available: ") + e.what();
  }
  if (auto why = order_skip_reason(c.solver, c.key.order)) return why;
  const LinearSystem& sys = linear_system(c.key);
  if (!sys.positive_definite && needs_spd(c.solver))
    return c.solver + " needs a positive-definite matrix; this one is " + sys.definiteness_note;
  return std::nullopt;
}

// Counters, the policy's record and the verdict of one repetition.
void report_linear(benchmark::State& state, const LinearCase& c, const LinearSystem& sys, const Sample& s,
                   const PeakMemory& memory, CaseProgress& progress) {
  const double unknowns = static_cast<double>(c.key.unknowns());
  state.counters["setup_s"] = s.setup_s;
  state.counters["solve_s"] = s.solve_s;
  state.counters["peak_MB"] = memory.peak_mb();
  state.counters["extra_MB"] = memory.extra_mb();
  state.counters["nonzeros"] = static_cast<double>(sys.K.nonZeros());
  state.counters["assembly_s"] = sys.assembly_seconds;
  const double residual = s.x.size() == sys.b.size() ? (sys.b - sys.K * s.x).norm() / sys.b.norm() : NAN;
  const bool ok = s.set_up && s.solved && residual <= 1e-6;
  progress.add(s.total(), memory.extra_mb(), ok);
  record_run(c.series(), c.level, c.solver, {unknowns, progress.median(), progress.extra_mb, progress.all_ok});
  if (!s.set_up) {
    if (sys.positive_definite)  // on an indefinite matrix a failure says nothing about the method
      record_setup_failure(c.solver, kind_tag(c.key), "set-up failed in BM_LinearSolve/" + c.key.tag() + "/" + c.solver + ": " + s.message);
    return fail(state, "set-up failed: " + s.message);
  }
  state.counters["iterations"] = s.iterations;
  state.counters["rel_residual"] = residual;
  if (!s.history.empty() && c.level <= kHistoryLevels && progress.seconds.size() == 1)
    add_history("BM_LinearSolve/" + c.key.tag() + "/" + c.solver, c.key.tag(), c.solver, unknowns, s.history);
  if (sys.has_exact && s.x.size() == sys.b.size()) {
    const auto err = solution_errors(sys, s.x);
    state.counters["l2_error"] = err.l2;
    state.counters["h1_error"] = err.h1;
  }
  const std::string spent = " (set-up " + std::to_string(s.setup_s) + " s, solve " + std::to_string(s.solve_s) + " s)";
  if (!s.solved) fail(state, s.message + spent);
  else if (!(residual <= 1e-6)) fail(state, "relative residual " + std::to_string(residual) + " after the solve" + spent);
}

void run_linear(benchmark::State& state, const LinearCase& c, CaseProgress& progress) {
  state.counters["unknowns"] = static_cast<double>(c.key.unknowns());
  state.counters["order"] = c.key.order;
  state.counters["level"] = c.level;
  state.SetLabel(c.key.tag() + " " + c.solver);
  if (!progress.decided) {
    try {
      progress.skip_reason = linear_skip_reason(c);
    } catch (const std::exception& e) {  // the system could not be built: a failure, not a choice
      return fail(state, std::string("the system could not be built: ") + e.what());
    }
    progress.decided = true;
  }
  if (progress.skip_reason) return skip(state, *progress.skip_reason);
  const LinearSystem& sys = linear_system(c.key);
  std::unique_ptr<LinearSolver> solver = make_solver(c.solver);
  const PeakMemory memory;
  Sample s;
  for (auto _ : state) s = solve_once(sys, *solver);  // the timed interval
  report_linear(state, c, sys, s, memory, progress);
}

void register_case(const LinearCase& c) {
  auto progress = std::make_shared<CaseProgress>();
  benchmark::RegisterBenchmark(("BM_LinearSolve/" + c.key.tag() + "/" + c.solver).c_str(),
                               [c, progress](benchmark::State& state) { run_linear(state, c, *progress); })
      ->Iterations(1)
      ->Repetitions(preset().repetitions_at(c.level))
      ->MeasureProcessCPUTime()
      ->Unit(benchmark::kMillisecond);
}

struct Kind {
  CellType cell;
  int order;
  int max_level;
};

// Sizes ascend within a (problem, kind) so that each size can be predicted and
// ranked from the one below.
void register_problem(const std::string& problem, const std::vector<Kind>& kinds) {
  const std::vector<std::string> solvers = linear_solver_names();
  for (const Kind& k : kinds)
    for (int level = 0; level <= k.max_level; ++level)
      for (const std::string& solver : solvers)
        register_case({{problem, k.cell, k.order, cubes_for_level(problem, k.cell, k.order, level)}, level, solver});
}

}  // namespace

void register_linear_sweep() {
  const int top = preset().max_level;
  // Hexahedra where cheap: one size below the tetrahedra (~1e4 quick, ~1e5 full).
  register_problem("mms-linear", {{CellType::Hexahedron, 1, top - 1},
                                  {CellType::Hexahedron, 2, top - 1},
                                  {CellType::Tetrahedron, 1, top},
                                  {CellType::Tetrahedron, 2, top},
                                  {CellType::Tetrahedron, 3, top}});
}

void register_hessian_sweep() {
  // The deformed-state Hessians up to one level below the MMS (~1e4 quick, ~1e5 full):
  // their definiteness is established by a CHOLMOD factorisation per system.
  const int top = preset().max_level - 1;
  for (const char* problem : {"hessian-nh", "hessian-nh-psd"})
    register_problem(problem, {{CellType::Tetrahedron, 1, top}, {CellType::Tetrahedron, 2, top}, {CellType::Tetrahedron, 3, top}});
}

}  // namespace hofem::bench
