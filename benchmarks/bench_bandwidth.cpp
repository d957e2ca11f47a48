// Memory-bandwidth benchmarks: the machine's floor from a STREAM-like triad, and
// sparse matrix-vector products and CG iterations on the elasticity matrices of
// the solver sweep (mms-linear, tetrahedra of order 1-3, ~1e5 unknowns; ~1e6 in
// the full preset) measured against it.
//
// The floor is triad_bytes_per_second() (bench_common.hpp), measured once in
// this process before the first benchmark that uses it; every ratio in a run
// refers to the same number. For each kernel:
//   bytes          data a kernel must move at least once per call: matrix values
//                  and row indices (8 + 8 bytes per nonzero, 64-bit indices),
//                  column starts, and every vector operand read or written,
//   floor_seconds  bytes / floor: the time at the triad's bandwidth,
//   floor_ratio    measured time / floor_seconds (1 = at the floor; the
//                  solver target is <= 1.5 for one CG iteration on the order-2 matrix),
//   bandwidth_ratio   achieved bytes/s over the floor (= 1 / floor_ratio),
//   floor_ratio_now   the same against a triad measured right after the kernel
//                  (triad_now_GBps): on a loaded machine the two floors differ.
// Google Benchmark's real_time and cpu_time are taken over the same interval,
// the kernel's loop (no manual timing: with it, cpu_time would cover the whole
// loop while real_time covers only what was reported).
#include "bench_common.hpp"

#include "assembly/assembler.hpp"
#include "study/manufactured_solution.hpp"
#include "linalg/block_sparse_matrix.hpp"
#include "linalg/krylov.hpp"
#include "linalg/linear_operator.hpp"
#include "solver/p_multigrid.hpp"
#include "linalg/preconditioner.hpp"
#include "solver/solver_factory.hpp"

#include <benchmark/benchmark.h>
#include <fmt/format.h>
#include <omp.h>

#include <string>

namespace hofem::bench {
namespace {

void set_floor_counters(benchmark::State& state, double bytes, double seconds_per_call, bool local_floor = true) {
  const double floor = triad_bytes_per_second();
  if (local_floor) {  // the triad again, right after the kernel: the ratio to it is less exposed to load drift
    const double now = measure_triad(3);
    state.counters["triad_now_GBps"] = now / 1e9;
    state.counters["floor_ratio_now"] = seconds_per_call / (bytes / now);
  }
  state.counters["bytes"] = bytes;
  state.counters["floor_GBps"] = floor / 1e9;
  state.counters["achieved_GBps"] = bytes / seconds_per_call / 1e9;
  state.counters["floor_seconds"] = bytes / floor;
  state.counters["floor_ratio"] = seconds_per_call / (bytes / floor);
  state.counters["bandwidth_ratio"] = (bytes / seconds_per_call) / floor;
}

// a = b + s c over three 64 MiB arrays, with 1 thread (the floor's kernel) or
// with every OpenMP thread (for comparison: on these 2-vCPU machines the second
// thread adds no bandwidth).
void BM_Triad(benchmark::State& state, bool threaded) {
  const Eigen::Index n = Eigen::Index{1} << 23;
  Eigen::VectorXd a = Eigen::VectorXd::Zero(n), b = Eigen::VectorXd::Constant(n, 1.0), c = Eigen::VectorXd::Constant(n, 2.0);
  double* pa = a.data();
  const double *pb = b.data(), *pc = c.data();
  const double s = 3.0;
  double total = 0.0;
  for (auto _ : state) {
    const auto t0 = Clock::now();
    if (threaded) {
#pragma omp parallel for schedule(static)
      for (Eigen::Index i = 0; i < n; ++i) pa[i] = pb[i] + s * pc[i];
    } else {
      for (Eigen::Index i = 0; i < n; ++i) pa[i] = pb[i] + s * pc[i];
    }
    benchmark::ClobberMemory();
    total += seconds_since(t0);
  }
  const double bytes = 24.0 * static_cast<double>(n);
  set_floor_counters(state, bytes, total / static_cast<double>(state.iterations()), false);
  state.counters["threads"] = threaded ? omp_get_max_threads() : 1;
  state.SetBytesProcessed(static_cast<std::int64_t>(bytes) * state.iterations());
  state.SetLabel(threaded ? "triad, all OpenMP threads" : "triad, 1 thread (the floor's kernel)");
}

// One CG iteration's seconds: (CG with many.max_iterations - CG with
// few.max_iterations) / their difference per benchmark iteration (the start and
// the final true-residual product cancel); returns their mean, which the caller
// reports as the counter seconds_per_iteration. Google Benchmark times the run
// with many.max_iterations only (the other runs with the timer paused), so its
// real_time and cpu_time are both that run's.
double time_cg_iteration(benchmark::State& state, const LinearOperator& A, const Eigen::VectorXd& b,
                         const Preconditioner& M, const KrylovOptions& few, const KrylovOptions& many) {
  Eigen::VectorXd x;
  auto timed = [&](const KrylovOptions& o) {
    x.setZero(b.size());
    const auto t0 = Clock::now();
    const KrylovResult r = conjugate_gradient(A, b, x, M, o);
    benchmark::DoNotOptimize(r.iterations);
    return seconds_since(t0);
  };
  double total = 0.0;
  for (auto _ : state) {
    state.PauseTiming();
    const double t_few = timed(few);
    state.ResumeTiming();
    total += (timed(many) - t_few) / (many.max_iterations - few.max_iterations);
  }
  state.counters["seconds_per_iteration"] = total / static_cast<double>(state.iterations());
  return total / static_cast<double>(state.iterations());
}

// The compute peak: independent FMA chains in the build's widest vectors on 1
// thread and on every OpenMP thread (element kernels quote their executed FLOPs
// beside it, BM_ElementKernel).
void BM_FmaPeak(benchmark::State& state, bool all_threads) {
  const int threads = all_threads ? omp_get_max_threads() : 1;
  double peak = 0.0;
  for (auto _ : state) peak = measure_fma_peak(threads);
  state.counters["GFLOPs"] = peak / 1e9;
  state.counters["threads"] = threads;
#if defined(__AVX512F__)
  state.SetLabel("AVX-512 FMA");
#elif defined(__AVX2__)
  state.SetLabel("AVX2 FMA");
#else
  state.SetLabel("scalar FMA");
#endif
}

// One iteration of CG preconditioned by the p-multigrid (the default solver of
// order >= 2, solver/solver_choice.cpp) on the linear manufactured-solution
// cube of BM_TimeToError: (CG with 12 iterations - CG with 4) / 8 (the counter
// seconds_per_iteration; the benchmark's time is the 12-iteration run), the operator
// the double-precision block copy, as KrylovSolver runs it. Bytes of one
// iteration: the block product (values, indices, operand, result), CG's vector
// traffic (17 vectors, as BM_CgIteration), and the preconditioner's
// PMultigridPreconditioner::bytes_per_apply(). The floor here is the triad on
// every thread measured right after (the iteration itself runs on every thread).
void BM_PmgIteration(benchmark::State& state, int order, int n) {
  hofem::MmsCase c;
  c.problem = "linear";
  c.order = order;
  c.n = n;
  const hofem::MmsProblem p(c);
  const DofMap dofs(p.mesh.num_nodes(), p.mesh.node_set("boundary"));
  const Assembler assembler(p.mesh, dofs, p.options.quadrature_degree);
  const Eigen::VectorXd x0 = Eigen::Map<const Eigen::VectorXd>(p.mesh.nodes.data(), 3 * p.mesh.num_nodes());
  Eigen::VectorXd g;
  SparseMatrix K;
  assembler.hessian(*p.material, x0, g, K, false);
  const Eigen::VectorXd b = dofs.restrict(assembler.body_force_vector(p.body_force, p.options.load_degree));
  const BlockSparseMatrix<double> blocks(K);
  PMultigridPreconditioner pmg;
  pmg.set_mesh_view({&p.mesh, &dofs});
  if (!pmg.setup(K, blocks)) return fail(state, pmg.last_error());
  const BlockOperator<double> A(blocks);
  KrylovOptions few, many;
  few.rtol = many.rtol = 0.0;  // never converged: exactly max_iterations iterations
  few.max_iterations = 4;
  many.max_iterations = 12;
  const double seconds = time_cg_iteration(state, A, b, pmg, few, many);
  const double rows = static_cast<double>(K.rows());
  const double product = static_cast<double>(blocks.bytes()) + 16.0 * rows, vectors = 17.0 * 8.0 * rows;
  const double bytes = product + vectors + pmg.bytes_per_apply();
  const double triad = measure_triad_all_threads(5);
  state.counters["bytes"] = bytes;
  state.counters["product_bytes"] = product;
  state.counters["preconditioner_bytes"] = pmg.bytes_per_apply();
  state.counters["triad_all_threads_GBps"] = triad / 1e9;
  state.counters["achieved_GBps"] = bytes / seconds / 1e9;
  state.counters["floor_seconds"] = bytes / triad;
  state.counters["floor_ratio"] = seconds / (bytes / triad);
  state.counters["unknowns"] = rows;
  state.counters["nonzeros"] = static_cast<double>(K.nonZeros());
  state.counters["order"] = order;
  state.counters["n"] = n;
  state.SetLabel(fmt::format("mms-linear/tet/p{}/n{} pmg-CG, 12 iterations (one: seconds_per_iteration)", order, n));
}

SystemKey matrix_key(int order, int level) {
  return {"mms-linear", CellType::Tetrahedron, order, cubes_for_level("mms-linear", CellType::Tetrahedron, order, level)};
}

double spmv_bytes(const SparseMatrix& A) {
  const double n = static_cast<double>(A.rows()), nnz = static_cast<double>(A.nonZeros());
  return 16.0 * nnz + 8.0 * (n + 1) + 16.0 * n;  // values + row indices, column starts, x read, y written
}

// y = A x as the Krylov solvers compute it (Eigen, compressed columns, 1 thread).
void run_spmv(benchmark::State& state, int order, int level) {
  const LinearSystem& sys = linear_system(matrix_key(order, level));
  const Eigen::VectorXd x = sys.b;
  Eigen::VectorXd y(x.size());
  double total = 0.0;
  for (auto _ : state) {
    const auto t0 = Clock::now();
    y.noalias() = sys.K * x;
    benchmark::DoNotOptimize(y.data());
    total += seconds_since(t0);
  }
  set_floor_counters(state, spmv_bytes(sys.K), total / static_cast<double>(state.iterations()));
  state.counters["unknowns"] = static_cast<double>(sys.K.rows());
  state.counters["nonzeros"] = static_cast<double>(sys.K.nonZeros());
  state.counters["order"] = order;
  state.SetLabel(sys.key.tag());
}

// One iteration of our Jacobi-preconditioned CG (linalg/krylov.cpp): the time of
// conjugate_gradient() with 25 iterations minus that with 5, over 20 (the start
// and the final true-residual product cancel), in the counter
// seconds_per_iteration; the benchmark's time is that of the 25-iteration run.
// Each benchmark iteration runs CG twice (30 CG iterations), so their number is
// fixed (2 per repetition) rather than left to --benchmark_min_time. Bytes of one iteration: one
// product A p plus the vector traffic of that implementation: p.Ap (2 vectors),
// x += a p (3), r -= a Ap (3), z = D^-1 r (3), r.z (2), p = z + b p (3), |r| (1).
void run_cg_iteration(benchmark::State& state, int order, int level) {
  const LinearSystem& sys = linear_system(matrix_key(order, level));
  auto jacobi = make_preconditioner("jacobi");
  jacobi->setup(sys.K);
  KrylovOptions few, many;
  few.rtol = many.rtol = 0.0;  // never converged: exactly max_iterations iterations
  few.max_iterations = 5;
  many.max_iterations = 25;
  const double seconds = time_cg_iteration(state, SparseMatrixOperator(sys.K), sys.b, *jacobi, few, many);
  const double n = static_cast<double>(sys.K.rows());
  const double vector_bytes = 17.0 * 8.0 * n;
  set_floor_counters(state, spmv_bytes(sys.K) + vector_bytes, seconds);
  state.counters["spmv_bytes"] = spmv_bytes(sys.K);
  state.counters["vector_bytes"] = vector_bytes;
  state.counters["unknowns"] = n;
  state.counters["nonzeros"] = static_cast<double>(sys.K.nonZeros());
  state.counters["order"] = order;
  state.SetLabel(sys.key.tag() + " jacobi-CG, 25 iterations (one: seconds_per_iteration)");
}

}  // namespace

void register_bandwidth() {
  // The floors: "threads:1" is the kernel of the floor every ratio refers to,
  // "threads:all" every OpenMP thread.
  for (bool all : {false, true}) {
    const std::string threads = all ? "threads:all" : "threads:1";
    benchmark::RegisterBenchmark(("BM_Triad/" + threads).c_str(), BM_Triad, all)->UseRealTime()->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark(("BM_FmaPeak/" + threads).c_str(), BM_FmaPeak, all)
        ->UseRealTime()
        ->Iterations(1)
        ->Unit(benchmark::kMillisecond);
  }
  // The time-to-error target's mesh (linear P3 n = 12); one repetition of 5
  // timed pairs (each repetition builds the problem anew, ~3 s).
  for (auto [order, n] : {std::pair{3, 12}})
    benchmark::RegisterBenchmark(fmt::format("BM_PmgIteration/mms-linear/tet/p{}/n{}", order, n).c_str(),
                                 [order, n](benchmark::State& s) { BM_PmgIteration(s, order, n); })
        ->UseRealTime()
        ->Iterations(5)
        ->Repetitions(1)
        ->Unit(benchmark::kMillisecond);
  const int top = preset().max_level;
  for (int level = 2; level <= top; ++level)
    for (int order = 1; order <= 3; ++order) {
      const std::string tag = matrix_key(order, level).tag();
      benchmark::RegisterBenchmark(("BM_SpMV/" + tag).c_str(), [order, level](benchmark::State& s) { run_spmv(s, order, level); })
          ->UseRealTime()
          ->Unit(benchmark::kMillisecond);
      benchmark::RegisterBenchmark(("BM_CgIteration/" + tag).c_str(),
                                   [order, level](benchmark::State& s) { run_cg_iteration(s, order, level); })
          ->UseRealTime()
          ->Iterations(2)
          ->Unit(benchmark::kMillisecond);
    }
}

}  // namespace hofem::bench
