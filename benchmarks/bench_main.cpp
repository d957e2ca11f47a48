// The benchmark executable's entry point: Google Benchmark with hofem's
// provenance (core/provenance) recorded in the JSON's context (machines are
// noisy; quote medians), progress lines on stderr beside the console table, and
// the configurations skipped on purpose kept out of the reports
// (bench_skip_reporter.hpp): their names and reasons go to the file named by
// HOFEM_BENCH_SKIPS_OUT, if set.
#include "bench_progress_reporter.hpp"
#include "bench_skip_reporter.hpp"
#include "provenance/provenance.hpp"

#include <benchmark/benchmark.h>

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <memory>
#include <string>
#include <string_view>

namespace {

// The value of Google Benchmark's flag --NAME=VALUE, read before Initialize()
// consumes the flags (1.7.1 does not export them), or of its environment
// variable (BENCHMARK_OUT for benchmark_out: the library's own fallback).
std::string flag_value(int argc, char** argv, std::string_view name, const char* env) {
  const std::string prefix = "--" + std::string(name) + "=";
  std::string value;
  if (const char* e = std::getenv(env)) value = e;
  for (int i = 1; i < argc; ++i)
    if (std::string_view(argv[i]).starts_with(prefix)) value = argv[i] + prefix.size();
  return value;
}

// The file reporter --benchmark_out_format asks for; Google Benchmark makes its
// own only when none is passed, and this one must sit behind the skip filter.
std::unique_ptr<benchmark::BenchmarkReporter> file_reporter(const std::string& format) {
  if (format.empty() || format == "json") return std::make_unique<benchmark::JSONReporter>();
  if (format == "console") return std::make_unique<benchmark::ConsoleReporter>(benchmark::ConsoleReporter::OO_None);
  std::fprintf(stderr, "hofem_bench: --benchmark_out_format=%s is not supported (json, console)\n", format.c_str());
  std::exit(2);
}

}  // namespace

int main(int argc, char** argv) {
  // Every provenance key as "hofem_<key>": Google Benchmark's own
  // "library_build_type" describes Debian's libbenchmark, not hofem.
  const char* preset = std::getenv("HOFEM_BENCH_PRESET");  // the solver sweep's (bench_common.hpp)
  // (Held in a variable: a range-for over items() of a temporary would read it after its end.)
  const nlohmann::json provenance = hofem::provenance_context(preset ? preset : "");
  for (const auto& [key, value] : provenance.items())  // "hofem_version" keeps its name
    benchmark::AddCustomContext(key.starts_with("hofem_") ? key : "hofem_" + key,
                                value.is_string() ? value.get<std::string>() : value.dump());
  benchmark::AddCustomContext("library_build_type_means", "the build of Debian's libbenchmark; hofem's is hofem_build_type");
  // Version of the preconditioner names: in files without this key (before
  // version 2), "ic0" named Eigen's incomplete Cholesky, today's "eigen-ict";
  // scripts/plots/solver_sweep_tables.py maps old names so results stay comparable.
  benchmark::AddCustomContext("preconditioner_names", "2");
  // Version of the benchmark names: from version 2 every name says what it
  // measures (BM_AssembleHessian/tet10/neohookean, not enum indices), skipped
  // configurations are absent (HOFEM_BENCH_SKIPS_OUT lists them) and the solver
  // sweep reports repetitions (Google Benchmark's aggregates) instead of one
  // in-run median.
  benchmark::AddCustomContext("benchmark_names", "2");
  const bool to_file = !flag_value(argc, argv, "benchmark_out", "BENCHMARK_OUT").empty();
  const std::string format = flag_value(argc, argv, "benchmark_out_format", "BENCHMARK_OUT_FORMAT");
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;

  hofem::bench::SkipLog skips;
  hofem::bench::ProgressConsoleReporter console(hofem::bench::benchmark_total_from_environment());
  // A skipped configuration is still one of the total the progress counts.
  hofem::bench::SkipFilter display(console, skips, [&](const std::string& name) { console.count(name); });
  std::unique_ptr<benchmark::BenchmarkReporter> file_inner = to_file ? file_reporter(format) : nullptr;
  std::unique_ptr<hofem::bench::SkipFilter> file;
  if (file_inner) file = std::make_unique<hofem::bench::SkipFilter>(*file_inner, skips);
  benchmark::RunSpecifiedBenchmarks(&display, file.get());
  benchmark::Shutdown();

  const char* out = std::getenv("HOFEM_BENCH_SKIPS_OUT");
  if (out && *out) {
    try {
      skips.write(out);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "hofem_bench: %s\n", e.what());
      return 1;
    }
  }
  if (skips.size() > 0)
    std::fprintf(stderr, "hofem_bench: %zu configurations skipped on purpose, not in the results (%s)\n", skips.size(),
                 out && *out ? out : "set HOFEM_BENCH_SKIPS_OUT=FILE for their names and reasons");
  return 0;
}
