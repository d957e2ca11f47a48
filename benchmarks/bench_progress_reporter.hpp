#pragma once
// Google Benchmark's console table (on stdout: scripts/run keeps it as a log
// under reports/logs/), plus progress lines on stderr (provenance/progress.hpp):
// the benchmark just finished, how many of HOFEM_BENCH_TOTAL are done and an
// estimate of what remains, and a heartbeat while a long one runs.
#include "provenance/progress.hpp"

#include <benchmark/benchmark.h>

#include <string>
#include <vector>

namespace hofem::bench {

class ProgressConsoleReporter : public benchmark::ConsoleReporter {
 public:
  /// `total`: the benchmarks the filter selects (0: unknown, no estimate).
  explicit ProgressConsoleReporter(int total);
  void ReportRuns(const std::vector<Run>& runs) override;
  void Finalize() override;
  /// Counts a benchmark as done (once per run name); ReportRuns calls it, and so
  /// may a filter that keeps a run from this reporter.
  void count(const std::string& name);

 private:
  ProgressLog log_;
  int total_;
  int done_ = 0;
  std::string last_;
};

/// HOFEM_BENCH_TOTAL from the environment (scripts/run counts with
/// --benchmark_list_tests), 0 if unset or not a number.
int benchmark_total_from_environment();

}  // namespace hofem::bench
