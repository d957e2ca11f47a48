// Assembly throughput: energy, gradient and Hessian per element type / order x
// material, and sparsity-pattern construction on its own (it is done once per
// mesh; the others run every Newton iteration). Counters: elements/s and
// quadrature points/s (rates over the measured time), DOFs, nonzeros.
#include "assembly/assembler.hpp"
#include "basis/basis_tabulation.hpp"
#include "bench_common.hpp"
#include "element/element_kernel.hpp"
#include "material/material.hpp"
#include "mesh/box_mesh.hpp"
#include "linalg/blas_threads.hpp"

#include <benchmark/benchmark.h>
#include <omp.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <map>
#include <memory>
#include <string>
#include <vector>
#include <thread>
#include <utility>

// BLAS's Fortran matrix product, from the OpenBLAS hofem links.
extern "C" void dgemm_(const char* transa, const char* transb, const int* m, const int* n, const int* k,
                       const double* alpha, const double* a, const int* lda, const double* b, const int* ldb,
                       const double* beta, double* c, const int* ldc);

namespace {

using namespace hofem;

struct Setup {
  Mesh mesh;
  DofMap dofs;
  std::unique_ptr<Assembler> assembler;
  Eigen::VectorXd x;
};

// Element type index -> (cell, order, cubes per side): sizes give 10^4 - 10^5 DOFs.
struct ElementKind {
  CellType cell;
  int order;
  int n;
  const char* label;
};
const ElementKind kKinds[] = {{CellType::Tetrahedron, 1, 16, "Tet4"},   {CellType::Tetrahedron, 2, 10, "Tet10"},
                              {CellType::Tetrahedron, 3, 7, "Tet20"},   {CellType::Hexahedron, 1, 24, "Hex8"},
                              {CellType::Hexahedron, 2, 12, "Hex20"}};
constexpr int kTet4 = 0, kTet10 = 1, kTet20 = 2, kHex20 = 4;  // indices into kKinds

// One mesh per kind, built once: a unit cube, xmin face clamped, deformed by a
// smooth displacement so that F != I at every quadrature point.
Setup& setup(int kind) {
  static std::map<int, std::unique_ptr<Setup>> cache;
  auto& s = cache[kind];
  if (!s) {
    s = std::make_unique<Setup>();
    const ElementKind& k = kKinds[kind];
    s->mesh = box_mesh(unit_cube(k.n), k.cell, k.order);
    s->dofs = DofMap(s->mesh.num_nodes(), s->mesh.node_set("xmin"));
    s->assembler = std::make_unique<Assembler>(s->mesh, s->dofs);
    s->x.resize(3 * s->mesh.num_nodes());
    for (int n = 0; n < s->mesh.num_nodes(); ++n) {
      const Eigen::Vector3d X = s->mesh.nodes.col(n);
      s->x.segment<3>(3 * n) = X + 0.05 * Eigen::Vector3d(std::sin(3 * X[1]), X[0] * X[2], std::cos(2 * X[0]) - 1);
    }
  }
  return *s;
}

// Every material of the registry (material/material_registry.hpp).
const std::vector<std::string> kMaterials = material_names();

void set_counters(benchmark::State& state, int kind, int material, const Setup& s) {
  const double elements = s.mesh.num_elements();
  const double points = elements * s.assembler->rule().size();
  state.counters["elements_per_s"] = benchmark::Counter(elements, benchmark::Counter::kIsIterationInvariantRate);
  state.counters["qpoints_per_s"] = benchmark::Counter(points, benchmark::Counter::kIsIterationInvariantRate);
  state.counters["dofs"] = s.dofs.num_free();
  state.counters["qpoints_per_element"] = s.assembler->rule().size();
  state.SetLabel(std::string(kKinds[kind].label) + " " + kMaterials[static_cast<size_t>(material)]);
}

void BM_AssembleEnergy(benchmark::State& state, int kind, int material) {
  Setup& s = setup(kind);
  const auto mat = make_material(kMaterials[static_cast<size_t>(material)], LameParameters::from_young_poisson(1.0, 0.3));
  for (auto _ : state) benchmark::DoNotOptimize(s.assembler->energy(*mat, s.x));
  set_counters(state, kind, material, s);
}

void BM_AssembleGradient(benchmark::State& state, int kind, int material) {
  Setup& s = setup(kind);
  const auto mat = make_material(kMaterials[static_cast<size_t>(material)], LameParameters::from_young_poisson(1.0, 0.3));
  Eigen::VectorXd g;
  for (auto _ : state) benchmark::DoNotOptimize(s.assembler->gradient(*mat, s.x, g));
  set_counters(state, kind, material, s);
}

void BM_AssembleHessian(benchmark::State& state, int kind, int material) {
  Setup& s = setup(kind);
  const auto mat = make_material(kMaterials[static_cast<size_t>(material)], LameParameters::from_young_poisson(1.0, 0.3));
  Eigen::VectorXd g;
  SparseMatrix K = s.assembler->new_matrix();
  for (auto _ : state) benchmark::DoNotOptimize(s.assembler->hessian(*mat, s.x, g, K, false));
  set_counters(state, kind, material, s);
  state.counters["nonzeros"] = static_cast<double>(K.nonZeros());
}

// The element Hessian kernel alone (gather and element_hessian, no scatter), on
// every OpenMP thread, against the FMA peak measured right after on as many
// threads: GFLOPs counts the FLOPs element_hessian executes
// (element_hessian_flops: geometry, F, forces, the E Gt product; the material's
// dP/dF not counted, so the fraction is a lower bound).
template <int N>
void element_kernel_loop(const Setup& s, const Material& mat, double& sink) {
  const Mesh& mesh = s.mesh;
  const BasisTabulation& tab = cached_tabulation(mesh.cell, mesh.order, s.assembler->quadrature_degree());
  const Eigen::VectorXd& w = s.assembler->rule().weights;
  double total = 0.0;
#pragma omp parallel reduction(+ : total)
  {
    ElementWorkspace<N> ws(mesh.nodes_per_element());
#pragma omp for schedule(static)
    for (int e = 0; e < mesh.num_elements(); ++e) {
      for (int i = 0; i < ws.nodes(); ++i) {
        const int node = mesh.elements(i, e);
        ws.X.col(i) = mesh.nodes.col(node);
        ws.x.col(i) = s.x.segment<3>(3 * node);
      }
      total += element_hessian(mat, tab, w, ws, false) + ws.hessian_entry(0, 1, 0, 2);
    }
  }
  sink += total;
}

void BM_ElementKernel(benchmark::State& state, int kind, int material) {
  Setup& s = setup(kind);
  const auto mat = make_material(kMaterials[static_cast<size_t>(material)], LameParameters::from_young_poisson(1.0, 0.3));
  double sink = 0.0;
  for (auto _ : state) {
    switch (s.mesh.nodes_per_element()) {
      case 10: element_kernel_loop<10>(s, *mat, sink); break;
      case 20: element_kernel_loop<20>(s, *mat, sink); break;
      default: element_kernel_loop<Eigen::Dynamic>(s, *mat, sink); break;
    }
  }
  benchmark::DoNotOptimize(sink);
  const double flops = element_hessian_flops(s.mesh.nodes_per_element(), s.assembler->rule().size()) *
                       static_cast<double>(s.mesh.num_elements());
  state.counters["GFLOPs"] = benchmark::Counter(flops / 1e9, benchmark::Counter::kIsIterationInvariantRate);
  state.counters["flops_per_element"] = flops / static_cast<double>(s.mesh.num_elements());
  state.counters["fma_peak_GFLOPs"] = bench::measure_fma_peak(omp_get_max_threads()) / 1e9;
  state.counters["threads"] = omp_get_max_threads();
  set_counters(state, kind, material, s);
}

// Hessian assembly with 1 and 2 OpenMP threads (Neo-Hookean): what the second core buys.
void BM_AssembleHessianThreads(benchmark::State& state, int kind, int threads) {
  Setup& s = setup(kind);
  const auto mat = make_material("neohookean", LameParameters::from_young_poisson(1.0, 0.3));
  const int previous = omp_get_max_threads();
  omp_set_num_threads(threads);
  Eigen::VectorXd g;
  SparseMatrix K = s.assembler->new_matrix();
  for (auto _ : state) benchmark::DoNotOptimize(s.assembler->hessian(*mat, s.x, g, K, false));
  omp_set_num_threads(previous);
  const double elements = s.mesh.num_elements();
  state.counters["elements_per_s"] = benchmark::Counter(elements, benchmark::Counter::kIsIterationInvariantRate);
  state.SetLabel(std::string(kKinds[kind].label) + " neohookean threads=" + std::to_string(threads));
}

// A direct solver's BLAS call followed by a Hessian assembly on every OpenMP
// thread, as in each Newton iteration of a small implicit problem: a 256 x 256
// matrix product (a supernode's update; OpenBLAS threads it when it may), then
// the Hex20 Neo-Hookean assembly. blas_threads:1 is what the direct solvers set
// below kThreadedBlasMinFlops (linalg/blas_threads.hpp); blas_threads:pool lets
// OpenBLAS's workers take the product, after which they spin on sched_yield for
// ~0.1 s beside the assembly's threads.
void BM_AssembleAfterBlas(benchmark::State& state, bool pool) {
  Setup& s = setup(kHex20);
  const auto mat = make_material("neohookean", LameParameters::from_young_poisson(1.0, 0.3));
  Eigen::VectorXd g;
  SparseMatrix K = s.assembler->new_matrix();
  const int n = 256;
  const Eigen::MatrixXd a = Eigen::MatrixXd::Random(n, n), b = Eigen::MatrixXd::Random(n, n);
  Eigen::MatrixXd c(n, n);
  const double one = 1.0, zero = 0.0;
  const int threads = use_blas_threads_for(pool ? kThreadedBlasMinFlops : 0.0);
  for (auto _ : state) {
    dgemm_("N", "N", &n, &n, &n, &one, a.data(), &n, b.data(), &n, &zero, c.data(), &n);
    benchmark::DoNotOptimize(s.assembler->hessian(*mat, s.x, g, K, false));
  }
  use_blas_threads_for(0.0);
  state.counters["blas_threads"] = threads;
  state.SetLabel("Hex20 neohookean after a threaded dgemm: blas threads " + std::to_string(threads));
}

// Pattern, element-to-nonzero map and colouring: once per mesh.
void BM_SparsityPattern(benchmark::State& state, int kind) {
  Setup& s = setup(kind);
  size_t map_bytes = 0;
  std::int64_t nnz = 0;
  for (auto _ : state) {
    SparsityPattern p(s.mesh, s.dofs);
    map_bytes = p.map_bytes();
    nnz = p.nonzeros();
    benchmark::DoNotOptimize(p);
  }
  state.counters["nonzeros"] = static_cast<double>(nnz);
  state.counters["map_MB"] = static_cast<double>(map_bytes) / 1e6;
  state.counters["elements_per_s"] =
      benchmark::Counter(static_cast<double>(s.mesh.num_elements()), benchmark::Counter::kIsIterationInvariantRate);
  state.SetLabel(kKinds[kind].label);
}

// Names say what is measured: BM_AssembleHessian/tet10/neohookean (element,
// then material), BM_AssembleHessianThreads/hex20/threads:2, stable across runs
// so that two result files pair up by name. Wall time: the kernels run on
// every OpenMP thread.
std::string element_name(int kind) {
  std::string n = kKinds[kind].label;
  std::transform(n.begin(), n.end(), n.begin(), [](unsigned char ch) { return static_cast<char>(std::tolower(ch)); });
  return n;
}

template <class Function, class... Args>
void register_named(const std::string& name, Function f, Args... args) {
  benchmark::RegisterBenchmark(name.c_str(), f, args...)->Unit(benchmark::kMillisecond)->UseRealTime();
}

const bool registered = [] {
  const int kinds = static_cast<int>(std::size(kKinds)), materials = static_cast<int>(kMaterials.size());
  using Assembly = void (*)(benchmark::State&, int, int);
  const std::pair<const char*, Assembly> families[] = {
      {"BM_AssembleEnergy", BM_AssembleEnergy}, {"BM_AssembleGradient", BM_AssembleGradient}, {"BM_AssembleHessian", BM_AssembleHessian}};
  for (const auto& [family, f] : families)
    for (int k = 0; k < kinds; ++k)
      for (int m = 0; m < materials; ++m)
        register_named(std::string(family) + "/" + element_name(k) + "/" + kMaterials[static_cast<size_t>(m)], f, k, m);
  for (int k : {kTet10, kTet20, kHex20})
    for (int m : {0, 3})  // linear, neohookean
      register_named("BM_ElementKernel/" + element_name(k) + "/" + kMaterials[static_cast<size_t>(m)], BM_ElementKernel, k, m);
  for (int k : {kTet4, kTet20, kHex20})
    for (int threads : {1, 2})
      register_named("BM_AssembleHessianThreads/" + element_name(k) + "/threads:" + std::to_string(threads),
                     BM_AssembleHessianThreads, k, threads);
  for (int k = 0; k < kinds; ++k) register_named("BM_SparsityPattern/" + element_name(k), BM_SparsityPattern, k);
  register_named("BM_AssembleAfterBlas/hex20/blas_threads:1", BM_AssembleAfterBlas, false);
  register_named("BM_AssembleAfterBlas/hex20/blas_threads:pool", BM_AssembleAfterBlas, true);
  return true;
}();

}  // namespace
