#pragma once
// Runs that were not made are not results. A benchmark that decides not to run
// a configuration (the solver sweep's policy, bench_policy.cpp; a missing input
// file) says so through skip() (bench_common.hpp). Google Benchmark 1.7.1 has
// no way to leave a run without an error (State::SkipWithError is the only
// exit), so such a run reaches the reporters as an error with zero time whose
// message starts with kSkipPrefix. SkipFilter stands in front of the display
// and the file reporter and takes those runs out: the timed JSON holds only
// runs that were made (runs made that failed, "failed: ...", stay in it as
// errors), so a comparison of two files (Google Benchmark's tools/compare.py
// pairs entries by name) never sets a configuration timed in one run against
// its zero-time skip in the other. SkipLog keeps the skipped configurations and
// their reasons; bench_main.cpp writes them to HOFEM_BENCH_SKIPS_OUT:
//
//   {"skipped": [{"name": "BM_LinearSolve/mms-linear/tet/p2/n12/cg+jacobi/iterations:1/repeats:1/process_time",
//                 "reason": "not among the 6 components predicted fastest at this size, preset quick (...)"}]}
//
// Why not decide before registration instead: the sweep's decisions at a size
// depend on the times measured at the sizes below in the same process, so they
// can only be made when a configuration's turn comes.
#include <benchmark/benchmark.h>

#include <cstddef>
#include <functional>
#include <set>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace hofem::bench {

inline constexpr std::string_view kSkipPrefix = "skipped: ";

/// The configurations skipped on purpose, each once (its repetitions, and the
/// display and file reporters, all see the same skip), in the order of the run.
class SkipLog {
 public:
  void add(const std::string& name, const std::string& reason);
  std::size_t size() const { return entries_.size(); }
  /// {"skipped": [{"name", "reason"}, ...]}, written complete or not at all.
  void write(const std::string& path) const;

 private:
  std::vector<std::pair<std::string, std::string>> entries_;
  std::set<std::string> names_;
};

/// Forwards every run but the skipped ones to `inner`, and logs those.
class SkipFilter final : public benchmark::BenchmarkReporter {
 public:
  /// `on_skip`, if given, hears the run name of each skipped run (the progress count).
  SkipFilter(benchmark::BenchmarkReporter& inner, SkipLog& log,
             std::function<void(const std::string&)> on_skip = {})
      : inner_(inner), log_(log), on_skip_(std::move(on_skip)) {}
  bool ReportContext(const Context& context) override;
  void ReportRuns(const std::vector<Run>& runs) override;
  void Finalize() override { inner_.Finalize(); }

 private:
  benchmark::BenchmarkReporter& inner_;
  SkipLog& log_;
  std::function<void(const std::string&)> on_skip_;
};

}  // namespace hofem::bench
