// Benchmarks of the foundation layers: building quadrature rules and building /
// tabulating Lagrange bases, per cell and order. Results go to JSON with
// --benchmark_out=FILE --benchmark_out_format=json (scripts/run does this).
//
// What is measured and why it matters: rules and tabulations are built once per
// (cell, order, degree) and then reused by every element, so these are set-up
// costs; the per-point evaluation benchmark is what a non-cached path would pay.
#include "basis/basis_tabulation.hpp"
#include "basis/reference_basis.hpp"
#include "quadrature/gauss_rules.hpp"
#include "quadrature/published_rules.hpp"
#include "quadrature/rule_library.hpp"

#include <benchmark/benchmark.h>



namespace {

using hofem::CellType;

CellType cell_arg(int64_t c) {
  return c == 0 ? CellType::Triangle : c == 1 ? CellType::Tetrahedron : CellType::Hexahedron;
}

void BM_GaussLegendre(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  for (auto _ : state) benchmark::DoNotOptimize(hofem::gauss_legendre(n));
  state.counters["points"] = n;
}
BENCHMARK(BM_GaussLegendre)->Arg(4)->Arg(16)->Arg(64)->Unit(benchmark::kMicrosecond);

void BM_CollapsedRule(benchmark::State& state) {
  const CellType cell = cell_arg(state.range(0));
  const int degree = static_cast<int>(state.range(1));
  int n = 0;
  for (auto _ : state) {
    auto r = hofem::gauss_collapsed(cell, degree);
    n = r.size();
    benchmark::DoNotOptimize(r);
  }
  state.SetLabel(std::string(hofem::name(cell)));
  state.counters["points"] = n;
}
BENCHMARK(BM_CollapsedRule)->ArgsProduct({{0, 1}, {4, 10, 20, 30}})->Unit(benchmark::kMicrosecond);

void BM_ParsePublishedRules(benchmark::State& state) {
  const CellType cell = cell_arg(state.range(0));
  size_t n = 0;
  for (auto _ : state) {
    auto rules = hofem::published_rules(cell);
    n = rules.size();
    benchmark::DoNotOptimize(rules);
  }
  state.SetLabel(std::string(hofem::name(cell)));
  state.counters["rules"] = static_cast<double>(n);
}
BENCHMARK(BM_ParsePublishedRules)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

void BM_BuildLagrangeBasis(benchmark::State& state) {
  const CellType cell = cell_arg(state.range(0));
  const int order = static_cast<int>(state.range(1));
  if (cell == CellType::Hexahedron && order > 2) {
    state.SkipWithError("hex bases: Hex8 and Hex20 only");
    return;
  }
  int size = 0;
  for (auto _ : state) {
    auto b = hofem::make_lagrange_basis(cell, order);
    size = b->size();
    benchmark::DoNotOptimize(b);
  }
  state.SetLabel(std::string(hofem::name(cell)));
  state.counters["basis_functions"] = size;
}
BENCHMARK(BM_BuildLagrangeBasis)->ArgsProduct({{0, 1}, {1, 2, 3, 4, 5, 6}})->Args({2, 1})->Args({2, 2})->Unit(benchmark::kMicrosecond);

// Tabulation over the rule an element of this order needs for a mass matrix
// (degree 2p): values + gradients of every basis function at every point.
void BM_Tabulate(benchmark::State& state) {
  const CellType cell = cell_arg(state.range(0));
  const int order = static_cast<int>(state.range(1));
  const hofem::ReferenceBasis& basis = hofem::lagrange_basis(cell, order);
  const hofem::QuadratureRule& rule = hofem::quadrature_rule(cell, 2 * order);
  for (auto _ : state) benchmark::DoNotOptimize(hofem::tabulate(basis, rule));
  state.SetLabel(std::string(hofem::name(cell)));
  state.counters["points"] = rule.size();
  state.counters["basis_functions"] = basis.size();
  // Entries (values + gradients) produced per second.
  state.counters["entries_per_s"] = benchmark::Counter(static_cast<double>(rule.size()) * basis.size() * (1 + basis.dim()),
                                                       benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_Tabulate)->ArgsProduct({{0, 1}, {1, 2, 3, 4, 5, 6}})->Args({2, 1})->Args({2, 2})->Unit(benchmark::kMicrosecond);

// The cached path: what every element after the first pays.
void BM_CachedTabulation(benchmark::State& state) {
  const int order = static_cast<int>(state.range(0));
  hofem::cached_tabulation(CellType::Tetrahedron, order, 2 * order);
  for (auto _ : state) benchmark::DoNotOptimize(&hofem::cached_tabulation(CellType::Tetrahedron, order, 2 * order));
}
BENCHMARK(BM_CachedTabulation)->Arg(1)->Arg(3)->Unit(benchmark::kNanosecond);

// One point, values and gradients, no cache: the cost a tabulation saves per use.
void BM_EvaluateAtPoint(benchmark::State& state) {
  const CellType cell = cell_arg(state.range(0));
  const int order = static_cast<int>(state.range(1));
  const hofem::ReferenceBasis& basis = hofem::lagrange_basis(cell, order);
  Eigen::VectorXd x = Eigen::VectorXd::Constant(basis.dim(), 0.2);
  Eigen::VectorXd v(basis.size());
  Eigen::MatrixXd g(basis.size(), basis.dim());
  for (auto _ : state) {
    basis.evaluate(x, v);
    basis.gradients(x, g);
    benchmark::DoNotOptimize(v.data());
    benchmark::DoNotOptimize(g.data());
  }
  state.SetLabel(std::string(hofem::name(cell)));
}
BENCHMARK(BM_EvaluateAtPoint)->ArgsProduct({{1}, {1, 2, 3, 4, 5, 6}})->Unit(benchmark::kNanosecond);

}  // namespace
