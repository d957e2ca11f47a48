// BM_ImplicitStep: one implicit Euler step of the twisting cylinder (Longva et
// al. 2020 §6.1's set-up: Stable Neo-Hookean, E = 5e6 Pa, nu = 0.48, dt = 1/30 s)
// from a stored mid-twist state (t = 1 s), per element family, with the linear
// solver "auto" chose and with CHOLMOD, in the same run. The rule behind "auto"
// (solver/solver_choice.hpp) is fitted to these rows.
//
// Families: Tet4, Tet10, Tet20 FEM (the conforming tube) and Hex8, Hex20 FCM
// (the tube embedded in a box grid). Sizes: ~1e4-4e4 unknowns in the quick
// preset (the main job); the seed's sizes with HOFEM_BENCH_PRESET=full
// (scripts/bench-full).
//
// The state at t = 1 s is made by running the scene from rest with "auto"
// (stored in benchmarks/data/implicit_step/NAME.state, keyed by the scene file
// and overrides; a state whose key differs is made again). Each repetition
// runs the scene for one step from that state in a fresh process state (mesh,
// finite-cell rules, mass, a new linear solver: nothing carried over from the
// previous repetition); the time is the step's own (manual time), its set-up
// is not in it.
//
// Counters: unknowns (free DOFs), Newton and Krylov iterations, set-ups
// (factorisations / preconditioner set-ups) and reuses, set-up / assembly /
// solve seconds of the step, peak RSS per unknown (the run's own, from an
// untimed run of the case: the process' high-water mark above its RSS at the
// start of the run, freed heap returned first; includes the mesh and the
// set-up), the RSS at that start.
#include "bench_common.hpp"
#include "scene/scene.hpp"
#include "scene/scene_runner.hpp"
#include "solver/solver_choice.hpp"

#include <benchmark/benchmark.h>
#include <fmt/format.h>
#include <malloc.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#ifndef HOFEM_SOURCE_DIR
#define HOFEM_SOURCE_DIR "."
#endif

namespace {

using namespace hofem;

struct StepCase {
  std::string name;    ///< benchmark and state file name
  std::string family;  ///< "Tet10 FEM", ...
  std::string scene;   ///< under scripts/scenes/
  std::vector<std::string> overrides;
  int order = 2;
  bool embedded = false;
  /// Also a row for the iterative path: "auto" is direct at this size, and the
  /// limit needs its crossover measured on both sides.
  bool iterative_row = false;
  /// A CHOLMOD row beside "auto" (not at 1e6 first-order unknowns: its factor
  /// alone would take most of the machine's memory and minutes per step).
  bool direct_row = true;
};

// The seed's twisting cylinder material and step (Longva et al. 2020 §6.1).
const std::vector<std::string> kTwist{"material.young=5e6", "material.poisson=0.48", "dt=0.03333333333333333"};
constexpr double kStateTime = 1.0;  // mid-twist: the top turns until t = 2 s

std::vector<StepCase> cases() {
  const bool full = bench::preset().name == "full";
  auto tube = [](int r, int a, int z) { return fmt::format("mesh.tube.cells=[{},{},{}]", r, a, z); };
  auto box = [](int x, int y, int z) { return fmt::format("mesh.box.cells=[{},{},{}]", x, y, z); };
  std::vector<StepCase> out;
  if (!full) {
    out = {{"tet4", "Tet4 FEM", "twisting-cylinder-p1.json", {tube(6, 48, 24)}, 1, false, true},
           {"tet10", "Tet10 FEM", "twisting-cylinder-p2.json", {tube(3, 24, 12)}, 2},
           {"tet20", "Tet20 FEM", "twisting-cylinder-p2.json", {"mesh.order=3", tube(2, 16, 8)}, 3},
           {"hex8-fcm", "Hex8 FCM", "twisting-cylinder-fcm-hex8.json", {box(20, 20, 30)}, 1, true},
           {"hex20-fcm", "Hex20 FCM", "twisting-cylinder-fcm-hex20.json", {box(10, 10, 15)}, 2, true}};
  } else {
    // The seed's sizes (Longva et al. 2020 Table 1): Hex20 FCM ~2,016 cells,
    // Tet10 ~17.7 k elements and the 86 k reference, Tet4 towards ~1e6 unknowns.
    out = {{"tet4-seed", "Tet4 FEM", "twisting-cylinder-p1.json", {tube(12, 96, 48)}, 1},
           // The seed's Tet4 reference class: ~1e6 unknowns (360 k nodes).
           {"tet4-million", "Tet4 FEM", "twisting-cylinder-p1.json", {tube(22, 176, 88)}, 1, false, false, false},
           {"tet10-seed", "Tet10 FEM", "twisting-cylinder-p2.json", {tube(3, 32, 16)}, 2},
           {"tet10-reference", "Tet10 FEM", "twisting-cylinder-p2.json", {tube(6, 64, 36)}, 2},
           {"tet20-seed", "Tet20 FEM", "twisting-cylinder-p2.json", {"mesh.order=3", tube(3, 32, 16)}, 3},
           {"hex8-fcm-seed", "Hex8 FCM", "twisting-cylinder-fcm-hex8.json", {box(28, 28, 42)}, 1, true},
           {"hex20-fcm-seed", "Hex20 FCM", "twisting-cylinder-fcm-hex20.json", {box(12, 12, 18)}, 2, true}};
  }
  for (StepCase& c : out) c.overrides.insert(c.overrides.begin(), kTwist.begin(), kTwist.end());
  return out;
}

std::string read_text(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// FNV-1a of the scene file and the overrides: the state's key.
std::string state_key(const StepCase& c, const std::string& scene_text) {
  std::uint64_t h = 1469598103934665603ull;
  auto mix = [&](const std::string& s) {
    for (unsigned char ch : s) h = (h ^ ch) * 1099511628211ull;
    h = (h ^ 0xff) * 1099511628211ull;
  };
  mix(scene_text);
  for (const std::string& o : c.overrides) mix(o);
  return fmt::format("{}:{:016x}@t={}", c.name, h, kStateTime);
}

// The stored state at t = 1 s, made (and stored) when missing or of another key.
StoredState mid_twist_state(const StepCase& c, const std::string& scene_path) {
  const std::string dir = std::string(HOFEM_SOURCE_DIR) + "/benchmarks/data/implicit_step";
  const std::string path = dir + "/" + c.name + ".state";
  const std::string key = state_key(c, read_text(scene_path));
  if (std::filesystem::exists(path)) {
    StoredState s = read_state(path);
    if (s.key == key) return s;
  }
  std::filesystem::create_directories(dir);
  std::vector<std::string> o = c.overrides;
  o.push_back(fmt::format("duration={}", kStateTime));
  SceneRunOptions run;
  run.write_frames = false;
  run.save_state = path;
  run.save_state_key = key;
  const SceneRunResult r = run_scene(read_scene(scene_path, o), "", run);
  if (!r.ok) throw std::runtime_error(fmt::format("{}: the run to t = {} s failed: {}", c.name, kStateTime, r.message));
  return read_state(path);
}

// A field of /proc/self/status in bytes ("VmHWM:", "VmRSS:").
double status_bytes(const char* field) {
  std::ifstream in("/proc/self/status");
  std::string line;
  while (std::getline(in, line))
    if (line.rfind(field, 0) == 0) return 1024.0 * std::stod(line.substr(std::string(field).size()));
  return 0.0;
}

// The memory one run adds to the process, measured in a run of its own before
// the timed ones: its peak is VmHWM after a reset (clear_refs 5 sets it to the
// current RSS), less the RSS at the reset. The heap that earlier cases freed is
// returned to the system first (malloc_trim): glibc keeps it otherwise, and the
// high-water mark would be an earlier, larger case's (a 23 k-unknown step read
// 61 kB per unknown that way, 1.4 GB). The timed runs do not trim: a trimmed
// heap is page-faulted again, which made the 354 k Tet10 step 4.8 -> 7.0 s, a
// first step's cost, not the per-step cost of a run that keeps its matrices.
struct RunMemory {
  double peak_bytes = 0.0;      ///< VmHWM during the run less the RSS before it
  double baseline_bytes = 0.0;  ///< the RSS before it (other cases' data, the state)
};
RunMemory measure_run_memory(const Scene& scene, const SceneRunOptions& run) {
  malloc_trim(0);
  std::ofstream("/proc/self/clear_refs") << "5";
  const double before = status_bytes("VmRSS:");
  const SceneRunResult r = run_scene(scene, "", run);
  if (!r.ok) throw std::runtime_error("the untimed run for its memory failed: " + r.message);
  return {status_bytes("VmHWM:") - before, before};
}

void BM_ImplicitStep(benchmark::State& state, const StepCase& c, const std::string& solver) {
  const std::string path = std::string(HOFEM_SOURCE_DIR) + "/scripts/scenes/" + c.scene;
  StoredState start;
  try {
    start = mid_twist_state(c, path);
  } catch (const std::exception& e) {
    return bench::fail(state, e.what());
  }
  std::vector<std::string> o = c.overrides;
  o.push_back(fmt::format("duration={:.17g}", start.t + 0.5 * (1.0 / 30.0)));  // one step: ceil((t_end - t) / dt)
  if (solver != "auto") o.push_back("solver.linear=" + solver);
  if (solver != "auto" && solver != "cholmod") o.push_back("solver.setup_reuse=amortised");  // as auto runs it
  const Scene scene = read_scene(path, o);
  SceneRunOptions run;
  run.write_frames = false;
  run.start = &start;
  // Once per case (the repetitions share it): its memory, untimed.
  static std::map<std::string, RunMemory> memory;
  const std::string key = c.name + "/" + solver;
  if (!memory.count(key)) {
    try {
      memory[key] = measure_run_memory(scene, run);
    } catch (const std::exception& e) {
      return bench::fail(state, e.what());
    }
  }
  double newton = 0, krylov = 0, setups = 0, reuses = 0, setup_s = 0, assembly_s = 0, solve_s = 0, n = 0;
  std::string chosen;
  for (auto _ : state) {
    const SceneRunResult r = run_scene(scene, "", run);
    if (!r.ok || r.stats["steps"].size() != 1) return bench::fail(state, r.message);
    const nlohmann::json& step = r.stats["steps"][0];
    const nlohmann::json& built = r.stats["built"];
    state.SetIterationTime(step["seconds"].get<double>());
    newton += step["newton_iterations"].get<double>();
    krylov += step["linear_iterations"].get<double>();
    setups += step["setups"].get<double>();
    reuses += step["setup_reuses"].get<double>();
    setup_s += built["setup_seconds"].get<double>();
    assembly_s += built["assembly_seconds"].get<double>();
    solve_s += built["solve_seconds"].get<double>();
    n = r.stats["free_dofs"].get<double>();
    chosen = built["linear_solver"].get<std::string>();
  }
  const double k = static_cast<double>(state.iterations());
  state.counters["unknowns"] = n;
  state.counters["newton_iterations"] = newton / k;
  state.counters["krylov_iterations"] = krylov / k;
  state.counters["setups"] = setups / k;
  state.counters["setup_reuses"] = reuses / k;
  state.counters["setup_s"] = setup_s / k;
  state.counters["assembly_s"] = assembly_s / k;
  state.counters["solve_s"] = solve_s / k;
  state.counters["peak_rss_bytes_per_unknown"] = n > 0 ? memory[key].peak_bytes / n : 0.0;  // the run's own
  state.counters["baseline_rss_bytes"] = memory[key].baseline_bytes;
  state.SetLabel(fmt::format("{}, {} ({})", c.family, solver, chosen));
}

// The iterative path "auto" takes above its direct limits (solver_choice.hpp,
// asked for 1e9 unknowns), with its set-up reuse: a third row where "auto"
// chose a direct solver at the case's size, so that each limit has its
// crossover measured on both sides. Families whose "auto" is iterative already
// have it as their "auto" row.
const bool registered = [] {
  for (const StepCase& c : cases()) {
    const std::string iterative =
        resolve_linear_solver(SolverSpec::parse("auto"), {1000000000, c.order, c.embedded}).spec.name();
    std::vector<std::string> solvers{"auto"};
    if (c.direct_row) solvers.push_back("cholmod");
    if (c.iterative_row) solvers.push_back(iterative);
    for (const std::string& solver : solvers)
      benchmark::RegisterBenchmark(fmt::format("BM_ImplicitStep/{}/{}", c.name, solver).c_str(), BM_ImplicitStep, c, solver)
          ->Unit(benchmark::kMillisecond)
          ->UseManualTime()
          ->Iterations(1)
          ->Repetitions(3);
  }
  return true;
}();

}  // namespace
