// Finite cell method (Longva et al. 2020 §4.4-4.5, §6.5) costs:
//  - BM_FcmQuadrature: generation (clipping + mapping, §4.5) and LP
//    simplification (§4.4) of the stiffness rules for an embedded geometry:
//    the hollow ball of scripts/meshes (scripts/make-meshes; skipped with the
//    reason when it is absent) in a Tet10 box grid, and a generated half tube in
//    a Hex20 grid (always available). Counters: points before / after, the
//    reduction factor, CPU seconds of generation and of simplification (summed
//    over threads), wall seconds. Longva et al. 2020: 5.86 M -> 70 k points (83x), 255 ms +
//    5.23 s on 28 cores.
//  - BM_ElasticStep: one implicit Euler step (Newton, CG + Additive Schwarz) of
//    the same body meshed conformingly (Tet10 tube) and embedded (FCM, Hex20
//    grid): seconds per step and CG iterations per step (Longva et al. 2020 §6.5 compare FEM
//    and FCM per step and in CG iterations).
#include "bench_common.hpp"
#include "dynamics/dynamic_elasticity.hpp"
#include "embedded/embedded_quadrature.hpp"
#include "embedded/finite_cell_quadrature.hpp"
#include "material/material.hpp"
#include "mesh/box_mesh.hpp"
#include "io/gmsh_reader.hpp"
#include "mesh/tube_mesh.hpp"

#include <benchmark/benchmark.h>

#include <filesystem>
#include <memory>

#ifndef HOFEM_SOURCE_DIR
#define HOFEM_SOURCE_DIR "."
#endif

namespace {

using namespace hofem;

void report_quadrature(benchmark::State& state, const CellQuadrature& q) {
  state.counters["points_before"] = static_cast<double>(q.points);
  state.counters["points_after"] = static_cast<double>(q.simplified_points);
  state.counters["reduction"] = q.simplified_points > 0 ? static_cast<double>(q.points) / q.simplified_points : 0.0;
  state.counters["generation_cpu_s"] = q.generation_seconds;
  state.counters["simplification_cpu_s"] = q.simplification_seconds;
  state.counters["wall_s"] = q.wall_seconds;
  state.counters["max_moment_residual"] = q.max_moment_residual;
  state.counters["lp_failures"] = q.simplification_failures;
  int cut = 0;
  for (size_t e = 0; e < q.volume_fraction.size(); ++e) cut += q.points_before[e] > 0;
  state.counters["cut_cells"] = cut;
}

void BM_FcmQuadrature_HollowBall(benchmark::State& state) {
  const std::string path = std::string(HOFEM_SOURCE_DIR) + "/scripts/meshes/hollow_ball.msh";
  if (!std::filesystem::exists(path)) {
    // Not a failure of the method: the input is made by another script.
    return bench::skip(state, "scripts/meshes/hollow_ball.msh is missing: run scripts/make-meshes (needs gmsh)");
  }
  const Mesh ball = read_gmsh(path);
  const std::vector<Tetrahedron> tets = mesh_tetrahedra(ball);
  Eigen::Vector3d lo = ball.nodes.rowwise().minCoeff(), hi = ball.nodes.rowwise().maxCoeff();
  const Mesh background = box_mesh(BoxSpec{{lo.x(), lo.y(), lo.z()}, {hi.x(), hi.y(), hi.z()}, {6, 6, 6}},
                                   CellType::Tetrahedron, 2);
  CellQuadrature q;
  for (auto _ : state) q = finite_cell_quadrature(background, tets);
  report_quadrature(state, q);
  state.counters["embedded_tets"] = static_cast<double>(tets.size());
}
// One run each (tens of seconds): the counters are what matters, not a median.
BENCHMARK(BM_FcmQuadrature_HollowBall)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(1)->Repetitions(1);

/// The half of a tube above y = 0 would do; the whole tube keeps the scene simple.
Mesh fine_tube() { return hollow_cylinder_mesh(0.5, 1.0, 2.0, 2, 48, 16, CellType::Tetrahedron, 1); }

void BM_FcmQuadrature_Tube(benchmark::State& state) {
  const Mesh tube = fine_tube();
  const std::vector<Tetrahedron> tets = mesh_tetrahedra(tube);
  const Mesh background = box_mesh(BoxSpec{{-1, -1, 0}, {1, 1, 2}, {4, 4, 4}}, CellType::Hexahedron, 2);
  CellQuadrature q;
  for (auto _ : state) q = finite_cell_quadrature(background, tets);
  report_quadrature(state, q);
  state.counters["embedded_tets"] = static_cast<double>(tets.size());
}
BENCHMARK(BM_FcmQuadrature_Tube)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(1)->Repetitions(1);

// One implicit Euler step of a tube sagging under gravity, clamped at z = 0:
// BM_ElasticStep/fem-tet10 = conforming Tet10 tube (FEM), BM_ElasticStep/fcm-hex20
// = the fine tube embedded in a Hex20 grid (FCM). Both precondition CG by the rule of Longva et al. 2020 §6.5: Schwarz blocks on cut
// cells under a volume fraction of 0.5, Jacobi elsewhere (for FEM: Jacobi only).
void BM_ElasticStep(benchmark::State& state, bool fcm) {
  const auto material = make_material("stable-neohookean", LameParameters::from_young_poisson(5e5, 0.4));
  DynamicsOptions o;
  o.integrator = Integrator::ImplicitEuler;
  o.dt = 1.0 / 60.0;
  o.gravity = Eigen::Vector3d(9.81, 0.0, 0.0);
  o.solver = SolverSpec::parse("cg+schwarz");
  Mesh mesh;
  std::vector<int> clamped;
  CellQuadrature q;
  if (fcm) {
    mesh = box_mesh(BoxSpec{{-1, -1, 0}, {1, 1, 2}, {4, 4, 4}}, CellType::Hexahedron, 2);
    q = finite_cell_quadrature(mesh, mesh_tetrahedra(fine_tube()));
    stabilise_finite_cells(mesh, q);
    o.element_rules = q.element_rules();
    o.preconditioner_blocks = schwarz_block_elements(q);  // cut cells under 0.5, as in Longva et al. 2020 §6.5
    clamped = mesh.node_set("zmin");
  } else {
    mesh = hollow_cylinder_mesh(0.5, 1.0, 2.0, 1, 12, 4, CellType::Tetrahedron, 2);
    o.preconditioner_blocks = std::vector<int>{};  // no cut cells: the same rule gives Jacobi everywhere
    clamped = mesh.node_set("bottom");
  }
  DynamicElasticity body(mesh, *material, {PrescribedMotion{clamped, {}, {}, {}}}, o);
  long long cg = 0, steps = 0;
  for (auto _ : state) {
    const StepReport r = body.step();
    if (!r.ok) return bench::fail(state, r.message);
    cg += r.linear_iterations;
    ++steps;
  }
  state.counters["cg_iterations_per_step"] = steps > 0 ? static_cast<double>(cg) / steps : 0.0;
  state.counters["free_dofs"] = body.dofs().num_free();
  state.SetLabel(fcm ? "FCM Hex20 (4x4x4 grid, 9216 embedded tets)" : "FEM Tet10 (tube 1x12x4)");
}
const bool registered = [] {
  for (bool fcm : {false, true})
    benchmark::RegisterBenchmark(fcm ? "BM_ElasticStep/fcm-hex20" : "BM_ElasticStep/fem-tet10", BM_ElasticStep, fcm)
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime()
        ->Iterations(20);
  return true;
}();

}  // namespace
