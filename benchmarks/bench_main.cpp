// The benchmark executable's entry point: Google Benchmark with hofem's
// provenance (core/provenance) recorded in the JSON's context (machines are
// noisy; quote medians), and progress lines on stderr beside the console table.
#include "bench_progress_reporter.hpp"
#include "provenance/provenance.hpp"

#include <benchmark/benchmark.h>

#include <cstdlib>
#include <string>

int main(int argc, char** argv) {
  // Every provenance key as "hofem_<key>": Google Benchmark's own
  // "library_build_type" describes Debian's libbenchmark, not hofem.
  const char* preset = std::getenv("HOFEM_BENCH_PRESET");  // the solver sweep's (bench_common.hpp)
  for (const auto& [key, value] : hofem::provenance_context(preset ? preset : "").items())
    benchmark::AddCustomContext("hofem_" + key, value.is_string() ? value.get<std::string>() : value.dump());
  benchmark::AddCustomContext("library_build_type_means", "the build of Debian's libbenchmark; hofem's is hofem_build_type");
  // Version of the preconditioner names: in files without this key (before
  // version 2), "ic0" named Eigen's incomplete Cholesky, today's "eigen-ict";
  // scripts/solver_sweep_tables.py maps old names so results stay comparable.
  benchmark::AddCustomContext("preconditioner_names", "2");
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  hofem::bench::ProgressConsoleReporter console(hofem::bench::benchmark_total_from_environment());
  benchmark::RunSpecifiedBenchmarks(&console);
  benchmark::Shutdown();
  return 0;
}
