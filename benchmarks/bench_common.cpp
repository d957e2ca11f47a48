// Shared pieces of the solver sweep (see bench_common.hpp): preset and sizes,
// the cache of linear systems, memory and bandwidth measurement, histories.
#include "bench_common.hpp"

#if defined(__AVX2__) || defined(__AVX512F__)
#include <immintrin.h>
#endif

#include "assembly/assembler.hpp"
#include "material/material.hpp"
#include "io/atomic_file.hpp"
#include "mesh/box_mesh.hpp"
#include "linalg/linear_solver.hpp"
#include "solver/solver_factory.hpp"
#include "basis/quadrature_degrees.hpp"

#include <malloc.h>
#include <nlohmann/json.hpp>
#include <sys/resource.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <list>
#include <map>
#include <tuple>

namespace hofem::bench {

// ---- preset and sizes -------------------------------------------------------

const Preset& preset() {
  static const Preset p = [] {
    const char* env = std::getenv("HOFEM_BENCH_PRESET");
    const std::string name = env && *env ? env : "quick";
    // quick: every combination at ~1e3, the 6 / 3 predicted fastest at ~1e4 / ~1e5,
    // 10 s per run; full: every combination up to ~1e5, the 4 predicted fastest
    // at ~1e6, 120 s per run; both 5 repetitions at ~1e3 and 1 above (bench_common.hpp).
    if (name == "quick") return Preset{"quick", 2, {0, 6, 3}, 10.0, {5, 1}, false};
    if (name == "full") return Preset{"full", 3, {0, 0, 0, 4}, 120.0, {5, 1}, true};
    std::fprintf(stderr, "hofem_bench: HOFEM_BENCH_PRESET='%s' (valid: quick, full)\n", name.c_str());
    std::exit(2);
  }();
  return p;
}

double level_target(int level) { return std::pow(10.0, level + 3); }

bool is_bar_problem(const std::string& problem) { return problem.rfind("hessian-nh", 0) == 0; }

long free_unknowns(const std::string& problem, CellType cell, int order, int n) {
  const long m = static_cast<long>(order) * n;  // lattice intervals across
  if (is_bar_problem(problem)) {  // both end faces clamped (tetrahedra, Hex8)
    const long length = static_cast<long>(kBarLength) * m;
    return 3 * (length - 1) * (m + 1) * (m + 1);
  }
  if (cell == CellType::Tetrahedron || order == 1) return 3 * (m - 1) * (m - 1) * (m - 1);
  // Hex20 (serendipity): interior vertices and interior edge midpoints only.
  const long v = n - 1;
  return 3 * (v * v * v + 3L * n * v * v);
}

int cubes_for_level(const std::string& problem, CellType cell, int order, int level) {
  const double target = level_target(level);
  auto distance = [&](int n) {
    const long u = free_unknowns(problem, cell, order, n);
    return u > 0 ? std::fabs(std::log(static_cast<double>(u) / target)) : 1e30;
  };
  int best = 1;
  for (int n = 2; n < 400; ++n)
    if (distance(n) < distance(best)) best = n;
  return best;
}

const char* cell_tag(CellType cell, int order) {
  if (cell == CellType::Tetrahedron) return "tet";
  return order == 1 ? "hex8" : "hex20";
}

// ---- linear systems ---------------------------------------------------------

bool SystemKey::operator<(const SystemKey& o) const {
  return std::tie(problem, cell, order, n) < std::tie(o.problem, o.cell, o.order, o.n);
}

std::string SystemKey::tag() const {
  return problem + "/" + cell_tag(cell, order) + "/p" + std::to_string(order) + "/n" + std::to_string(n);
}

namespace {

// The "hessian-nh" state: the bar shortened uniformly by 35 % along its axis,
// ends clamped, sides free. A clamped-clamped column of slenderness 4 buckles at
// ~20 % axial strain (Euler: pi^2 h^2 / (3 L^2)), so the unprojected Hessian here
// has negative eigenvalues (its buckling modes); the CHOLMOD factorisation in
// build_system confirms it for every size. Elements stay far from inversion
// (det F = 0.65), and Neo-Hookean's dP/dF is indefinite at every point.
constexpr double kCompression = 0.35;

std::unique_ptr<LinearSystem> build_system(const SystemKey& key) {
  auto s = std::make_unique<LinearSystem>();
  s->key = key;
  const bool mms = key.problem == "mms-linear";
  if (!mms && key.problem != "hessian-nh" && key.problem != "hessian-nh-psd")
    throw std::invalid_argument("unknown benchmark problem " + key.problem);
  std::unique_ptr<Material> neo_hookean;
  std::vector<int> clamped;
  if (mms) {
    hofem::MmsCase c;
    c.problem = "linear";
    c.solver = SolverSpec::parse("cholmod");  // the default options (this builds the system only)
    c.cell = key.cell;
    c.order = key.order;
    c.n = key.n;
    s->mms = std::make_unique<hofem::MmsProblem>(c);
    clamped = s->mms->mesh.node_set("boundary");
  } else {
    const BoxSpec bar{{0, 0, 0}, {kBarLength, 1, 1}, {static_cast<int>(kBarLength) * key.n, key.n, key.n}};
    s->bar = box_mesh(bar, key.cell, key.order);
    clamped = s->bar.node_set("xmin");
    const auto& xmax = s->bar.node_set("xmax");
    clamped.insert(clamped.end(), xmax.begin(), xmax.end());
    neo_hookean = make_material("neohookean", LameParameters::from_young_poisson(1.0, 0.3));
  }
  const Mesh& mesh = s->mesh();
  s->dofs = DofMap(mesh.num_nodes(), clamped);
  // The assembler (pattern, element-to-nonzero map) is dropped after assembly:
  // the sweep needs only K and b.
  const auto t0 = Clock::now();
  const int degree = mms ? s->mms->options.quadrature_degree : default_quadrature_degrees(key.cell, key.order).stiffness;
  const Assembler a(mesh, s->dofs, degree);
  s->u_fixed = Eigen::VectorXd::Zero(3 * mesh.num_nodes());
  Eigen::VectorXd x = Eigen::Map<const Eigen::VectorXd>(mesh.nodes.data(), 3 * mesh.num_nodes());
  if (mms) {
    for (int n : clamped) s->u_fixed.segment<3>(3 * n) = s->mms->ustar.value(mesh.nodes.col(n));
    x += s->u_fixed;  // free DOFs zero: for a linear material g = K_fc u_c
  } else {
    for (int n = 0; n < mesh.num_nodes(); ++n) x[3 * n] *= 1.0 - kCompression;
  }
  Eigen::VectorXd g;
  s->K = a.new_matrix();
  a.hessian(mms ? *s->mms->material : *neo_hookean, x, g, s->K, key.problem == "hessian-nh-psd");
  if (mms) {
    const Eigen::VectorXd f = a.body_force_vector(s->mms->body_force, s->mms->options.load_degree);
    s->b = s->dofs.restrict(f - g);  // K u_f = f - K_fc u_c
  } else {
    s->b = -s->dofs.restrict(g);  // the Newton system K d = -g
  }
  s->has_exact = mms;
  s->assembly_seconds = seconds_since(t0);
  if (!mms) {
    auto chol = make_linear_solver("cholmod");
    chol->analyze(s->K);
    s->positive_definite = chol->factorize(s->K);
    s->definiteness_note = s->positive_definite ? "positive definite (CHOLMOD factorises it)"
                                                : "indefinite (CHOLMOD reports it not positive definite)";
  }
  return s;
}

}  // namespace

const LinearSystem& linear_system(const SystemKey& key) {
  static std::list<std::unique_ptr<LinearSystem>> cache;  // most recently used first
  for (auto it = cache.begin(); it != cache.end(); ++it)
    if (!((*it)->key < key) && !(key < (*it)->key)) {
      cache.splice(cache.begin(), cache, it);
      return *cache.front();
    }
  // Drop old systems first so that the new one's memory does not add to them.
  auto cached_unknowns = [&] {
    double total = 0.0;
    for (const auto& s : cache) total += static_cast<double>(s->b.size());
    return total;
  };
  while (!cache.empty() && (cache.size() >= 4 || cached_unknowns() + static_cast<double>(key.unknowns()) > 2.5e6))
    cache.pop_back();
  cache.push_front(build_system(key));
  return *cache.front();
}

hofem::MmsErrors solution_errors(const LinearSystem& s, const Eigen::VectorXd& x) {
  if (!s.has_exact) {
    hofem::MmsErrors none;
    none.l2 = none.h1 = std::numeric_limits<double>::quiet_NaN();
    return none;
  }
  Eigen::VectorXd u = s.u_fixed;
  s.dofs.add_free(x, u);
  return hofem::mms_errors(s.mesh(), s.mms->ustar, u);
}

// ---- measurement ------------------------------------------------------------

namespace {

double status_mb(const char* field) {
  std::ifstream in("/proc/self/status");
  std::string line;
  const std::string key = std::string(field) + ":";
  while (std::getline(in, line))
    if (line.rfind(key, 0) == 0) return std::atof(line.c_str() + key.size()) / 1024.0;  // kB
  return std::numeric_limits<double>::quiet_NaN();
}

}  // namespace

PeakMemory::PeakMemory() {
  // Freed memory that the allocator keeps would be reused silently and hide a
  // run's own peak: on the first measurement, blocks >= 1 MiB are made to come
  // from (and return to) the system, and each measurement starts by trimming
  // the heap, so the resident size at the start is close to the live data.
  static const bool configured = [] {
    mallopt(M_MMAP_THRESHOLD, 1 << 20);
    mallopt(M_TRIM_THRESHOLD, 1 << 20);
    return true;
  }();
  (void)configured;
  malloc_trim(0);
  std::ofstream clear("/proc/self/clear_refs");
  clear << "5";
  clear.flush();
  resettable = static_cast<bool>(clear);
  start_mb = status_mb("VmRSS");
}

double PeakMemory::peak_mb() const {
  if (resettable) return status_mb("VmHWM");
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_maxrss) / 1024.0;
}

double memory_available_mb() {
  std::ifstream in("/proc/meminfo");
  std::string line;
  while (std::getline(in, line))
    if (line.rfind("MemAvailable:", 0) == 0) return std::atof(line.c_str() + 13) / 1024.0;
  return 4096.0;
}

double measure_triad(int passes) {
  const std::size_t n = std::size_t{64} << 17;  // 8 Mi doubles = 64 MiB per array
  Eigen::VectorXd a = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(n)), b = a.array() + 1.0, c = a.array() + 2.0;
  double* pa = a.data();
  const double *pb = b.data(), *pc = c.data();
  const double scalar = 3.0;
  double best = 1e30;
  for (int pass = 0; pass < passes; ++pass) {
    const auto t0 = Clock::now();
    for (std::size_t i = 0; i < n; ++i) pa[i] = pb[i] + scalar * pc[i];
    benchmark::ClobberMemory();
    best = std::min(best, seconds_since(t0));
  }
  benchmark::DoNotOptimize(a.data());
  return 24.0 * static_cast<double>(n) / best;
}

double measure_triad_all_threads(int passes) {
  const Eigen::Index n = Eigen::Index{64} << 17;
  Eigen::VectorXd a(n), b(n), c(n);
  double* pa = a.data();
  double* pb = b.data();
  double* pc = c.data();
#pragma omp parallel for schedule(static)
  for (Eigen::Index i = 0; i < n; ++i) pa[i] = 0.0, pb[i] = 1.0, pc[i] = 2.0;  // first touch on the threads that use it
  const double scalar = 3.0;
  double best = 1e30;
  for (int pass = 0; pass < passes; ++pass) {
    const auto t0 = Clock::now();
#pragma omp parallel for schedule(static)
    for (Eigen::Index i = 0; i < n; ++i) pa[i] = pb[i] + scalar * pc[i];
    benchmark::ClobberMemory();
    best = std::min(best, seconds_since(t0));
  }
  benchmark::DoNotOptimize(a.data());
  return 24.0 * static_cast<double>(n) / best;
}

namespace {

// 12 independent FMA chains (latency 4 cycles x 2 FMA pipes needs >= 8), each a
// vector of the build's widest type; `steps` rounds. Returns the FLOPs done.
double fma_chains(long steps, double* sink) {
#if defined(__AVX512F__)
  using V = __m512d;
  constexpr int kLanes = 8;
  auto fma = [](V a, V m, V c) { return _mm512_fmadd_pd(a, m, c); };
  V m = _mm512_set1_pd(0.999999), c = _mm512_set1_pd(1e-9);
  V a0 = _mm512_set1_pd(1.0), a1 = a0, a2 = a0, a3 = a0, a4 = a0, a5 = a0, a6 = a0, a7 = a0, a8 = a0, a9 = a0, a10 = a0, a11 = a0;
  auto sum = [](V v) { return _mm512_reduce_add_pd(v); };
#elif defined(__AVX2__) && defined(__FMA__)
  using V = __m256d;
  constexpr int kLanes = 4;
  auto fma = [](V a, V m, V c) { return _mm256_fmadd_pd(a, m, c); };
  V m = _mm256_set1_pd(0.999999), c = _mm256_set1_pd(1e-9);
  V a0 = _mm256_set1_pd(1.0), a1 = a0, a2 = a0, a3 = a0, a4 = a0, a5 = a0, a6 = a0, a7 = a0, a8 = a0, a9 = a0, a10 = a0, a11 = a0;
  auto sum = [](V v) {
    alignas(32) double t[4];
    _mm256_store_pd(t, v);
    return t[0] + t[1] + t[2] + t[3];
  };
#else
  using V = double;
  constexpr int kLanes = 1;
  auto fma = [](V a, V m, V c) { return std::fma(a, m, c); };
  V m = 0.999999, c = 1e-9;
  V a0 = 1.0, a1 = a0, a2 = a0, a3 = a0, a4 = a0, a5 = a0, a6 = a0, a7 = a0, a8 = a0, a9 = a0, a10 = a0, a11 = a0;
  auto sum = [](V v) { return v; };
#endif
  for (long i = 0; i < steps; ++i) {
    a0 = fma(a0, m, c), a1 = fma(a1, m, c), a2 = fma(a2, m, c), a3 = fma(a3, m, c);
    a4 = fma(a4, m, c), a5 = fma(a5, m, c), a6 = fma(a6, m, c), a7 = fma(a7, m, c);
    a8 = fma(a8, m, c), a9 = fma(a9, m, c), a10 = fma(a10, m, c), a11 = fma(a11, m, c);
  }
  *sink = sum(a0) + sum(a1) + sum(a2) + sum(a3) + sum(a4) + sum(a5) + sum(a6) + sum(a7) + sum(a8) + sum(a9) +
          sum(a10) + sum(a11);
  return 12.0 * 2.0 * kLanes * static_cast<double>(steps);
}

}  // namespace

double measure_fma_peak(int threads) {
  const long steps = 20'000'000;  // ~0.1 s at the peak of these machines
  double best = 0.0;
  for (int pass = 0; pass < 3; ++pass) {
    double flops = 0.0, sink = 0.0;
    const auto t0 = Clock::now();
#pragma omp parallel num_threads(threads) reduction(+ : flops, sink)
    {
      double s = 0.0;
      flops += fma_chains(steps, &s);
      sink += s;
    }
    benchmark::DoNotOptimize(sink);
    best = std::max(best, flops / seconds_since(t0));
  }
  return best;
}

double triad_bytes_per_second() {
  static const double bandwidth = measure_triad(10);
  return bandwidth;
}

// ---- residual histories -----------------------------------------------------

namespace {

struct HistoryStore {
  std::string path;
  nlohmann::json runs = nlohmann::json::array();
  HistoryStore() {
    const char* env = std::getenv("HOFEM_BENCH_HISTORY_OUT");
    if (env) path = env;
  }
  ~HistoryStore() {
    if (path.empty()) return;
    try {
      write_file_atomically(path, nlohmann::json{{"preset", preset().name}, {"runs", runs}}.dump(1) + "\n");
    } catch (const std::exception& e) {
      std::fprintf(stderr, "hofem_bench: %s\n", e.what());
    }
  }
};

HistoryStore& store() {
  static HistoryStore s;
  return s;
}

}  // namespace

bool histories_wanted() { return !store().path.empty(); }

void add_history(const std::string& benchmark, const std::string& problem, const std::string& solver, double unknowns,
                 const std::vector<double>& history) {
  if (!histories_wanted() || history.empty()) return;
  // At most ~300 points per run: every iteration up to 100, then geometrically
  // spaced ones, and always the last.
  std::vector<int> it;
  std::vector<double> res;
  const int n = static_cast<int>(history.size());
  for (int k = 0; k < n; k = k < 100 ? k + 1 : std::max(k + 1, static_cast<int>(k * 1.02))) {
    it.push_back(k);
    res.push_back(history[k]);
  }
  if (it.back() != n - 1) {
    it.push_back(n - 1);
    res.push_back(history.back());
  }
  store().runs.push_back({{"benchmark", benchmark},
                          {"problem", problem},
                          {"solver", solver},
                          {"unknowns", unknowns},
                          {"iterations", n - 1},
                          {"iteration", it},
                          {"relative_residual", res}});
}

namespace {

// One registration, in a fixed order: the manufactured-solution linear sweep,
// the bandwidth benchmarks (whose matrices are that sweep's ~1e5 systems, often
// still cached), the deformed-Hessian sweep, then the Newton sweep.
[[maybe_unused]] const bool registered = [] {
  register_linear_sweep();
  register_bandwidth();
  register_hessian_sweep();
  register_newton_sweep();
  return true;
}();

}  // namespace

}  // namespace hofem::bench
