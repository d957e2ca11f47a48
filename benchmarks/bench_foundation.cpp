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

#include <string>
#include <utility>
#include <vector>

namespace {

using hofem::CellType;

void BM_GaussLegendre(benchmark::State& state, int n) {
  for (auto _ : state) benchmark::DoNotOptimize(hofem::gauss_legendre(n));
  state.counters["points"] = n;
}

void BM_CollapsedRule(benchmark::State& state, CellType cell, int degree) {
  int n = 0;
  for (auto _ : state) {
    auto r = hofem::gauss_collapsed(cell, degree);
    n = r.size();
    benchmark::DoNotOptimize(r);
  }
  state.SetLabel(std::string(hofem::name(cell)));
  state.counters["points"] = n;
}

void BM_ParsePublishedRules(benchmark::State& state, CellType cell) {
  size_t n = 0;
  for (auto _ : state) {
    auto rules = hofem::published_rules(cell);
    n = rules.size();
    benchmark::DoNotOptimize(rules);
  }
  state.SetLabel(std::string(hofem::name(cell)));
  state.counters["rules"] = static_cast<double>(n);
}

void BM_BuildLagrangeBasis(benchmark::State& state, CellType cell, int order) {
  int size = 0;
  for (auto _ : state) {
    auto b = hofem::make_lagrange_basis(cell, order);
    size = b->size();
    benchmark::DoNotOptimize(b);
  }
  state.SetLabel(std::string(hofem::name(cell)));
  state.counters["basis_functions"] = size;
}

// Tabulation over the rule an element of this order needs for a mass matrix
// (degree 2p): values + gradients of every basis function at every point.
void BM_Tabulate(benchmark::State& state, CellType cell, int order) {
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

// The cached path: what every element after the first pays.
void BM_CachedTabulation(benchmark::State& state, int order) {
  hofem::cached_tabulation(CellType::Tetrahedron, order, 2 * order);
  for (auto _ : state) benchmark::DoNotOptimize(&hofem::cached_tabulation(CellType::Tetrahedron, order, 2 * order));
}

// One point, values and gradients, no cache: the cost a tabulation saves per use.
void BM_EvaluateAtPoint(benchmark::State& state, CellType cell, int order) {
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

// Names say what is measured, in a fixed order: the benchmark, the cell
// ("triangle", "tet", "hex"), then parameter:value (BM_Tabulate/tet/order:3),
// so that two result files pair up by name and a reader needs no table of
// enum indices.
std::string named(const char* benchmark, CellType cell, const char* parameter, int value) {
  return std::string(benchmark) + "/" + std::string(hofem::name(cell)) + "/" + parameter + ":" + std::to_string(value);
}

const bool registered = [] {
  for (int n : {4, 16, 64})
    benchmark::RegisterBenchmark(("BM_GaussLegendre/points:" + std::to_string(n)).c_str(), BM_GaussLegendre, n)
        ->Unit(benchmark::kMicrosecond);
  for (CellType cell : {CellType::Triangle, CellType::Tetrahedron}) {
    for (int degree : {4, 10, 20, 30})
      benchmark::RegisterBenchmark(named("BM_CollapsedRule", cell, "degree", degree).c_str(), BM_CollapsedRule, cell, degree)
          ->Unit(benchmark::kMicrosecond);
    benchmark::RegisterBenchmark(("BM_ParsePublishedRules/" + std::string(hofem::name(cell))).c_str(), BM_ParsePublishedRules, cell)
        ->Unit(benchmark::kMillisecond);
  }
  // Simplices of orders 1-6; hexahedra Hex8 and Hex20 only (the serendipity Hex20 is the highest hex basis).
  const std::vector<std::pair<CellType, std::vector<int>>> bases = {
      {CellType::Triangle, {1, 2, 3, 4, 5, 6}}, {CellType::Tetrahedron, {1, 2, 3, 4, 5, 6}}, {CellType::Hexahedron, {1, 2}}};
  for (const auto& [cell, orders] : bases)
    for (int order : orders) {
      benchmark::RegisterBenchmark(named("BM_BuildLagrangeBasis", cell, "order", order).c_str(), BM_BuildLagrangeBasis, cell, order)
          ->Unit(benchmark::kMicrosecond);
      benchmark::RegisterBenchmark(named("BM_Tabulate", cell, "order", order).c_str(), BM_Tabulate, cell, order)
          ->Unit(benchmark::kMicrosecond);
    }
  for (int order : {1, 3})
    benchmark::RegisterBenchmark(named("BM_CachedTabulation", CellType::Tetrahedron, "order", order).c_str(), BM_CachedTabulation, order)
        ->Unit(benchmark::kNanosecond);
  for (int order = 1; order <= 6; ++order)
    benchmark::RegisterBenchmark(named("BM_EvaluateAtPoint", CellType::Tetrahedron, "order", order).c_str(), BM_EvaluateAtPoint,
                                 CellType::Tetrahedron, order)
        ->Unit(benchmark::kNanosecond);
  return true;
}();

}  // namespace
