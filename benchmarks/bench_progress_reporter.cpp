#include "bench_progress_reporter.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <cstdlib>

namespace hofem::bench {

// Colours only on a terminal: the table is kept as a log file.
ProgressConsoleReporter::ProgressConsoleReporter(int total)
    : benchmark::ConsoleReporter(isatty(STDOUT_FILENO) ? OO_Defaults : OO_Tabular), log_("bench"), total_(total) {}

void ProgressConsoleReporter::ReportRuns(const std::vector<Run>& runs) {
  benchmark::ConsoleReporter::ReportRuns(runs);
  if (!runs.empty()) count(runs.front().run_name.str());
}

void ProgressConsoleReporter::count(const std::string& name) {
  // Repetitions and their aggregates arrive in separate calls under one run name.
  if (name == last_) return;
  last_ = name;
  ++done_;
  const std::string what = total_ > 0 ? fmt::format("[{}/{}] {}", done_, total_, name) : name;
  log_.stage(what, total_ > 0 ? static_cast<double>(done_) / total_ : 0.0);
}

void ProgressConsoleReporter::Finalize() {
  benchmark::ConsoleReporter::Finalize();
  log_.done(fmt::format("{} benchmarks", done_));
}

int benchmark_total_from_environment() {
  const char* text = std::getenv("HOFEM_BENCH_TOTAL");
  if (!text) return 0;
  char* end = nullptr;
  const long n = std::strtol(text, &end, 10);
  return (end != text && *end == '\0' && n > 0 && n < 1000000) ? static_cast<int>(n) : 0;
}

}  // namespace hofem::bench
