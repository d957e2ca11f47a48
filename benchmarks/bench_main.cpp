// The benchmark executable's entry point: Google Benchmark with the build and
// thread context recorded in the JSON (machines are noisy; quote medians).
#include <benchmark/benchmark.h>
#include <omp.h>

#include <string>
#include <thread>

int main(int argc, char** argv) {
  benchmark::AddCustomContext("hofem_build", HOFEM_BUILD_DESCRIPTION);
  benchmark::AddCustomContext("hardware_threads", std::to_string(std::thread::hardware_concurrency()));
  benchmark::AddCustomContext("omp_max_threads", std::to_string(omp_get_max_threads()));
  // Version of the preconditioner names: in files without this key (before
  // version 2), "ic0" named Eigen's incomplete Cholesky, today's "eigen-ict";
  // scripts/solver_sweep_tables.py maps old names so results stay comparable.
  benchmark::AddCustomContext("preconditioner_names", "2");
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
