// Skipped runs out of the reports, into their own record (bench_skip_reporter.hpp).
#include "bench_skip_reporter.hpp"

#include "io/atomic_file.hpp"

#include <nlohmann/json.hpp>

namespace hofem::bench {

void SkipLog::add(const std::string& name, const std::string& reason) {
  if (names_.insert(name).second) entries_.emplace_back(name, reason);
}

void SkipLog::write(const std::string& path) const {
  nlohmann::json skipped = nlohmann::json::array();
  for (const auto& [name, reason] : entries_) skipped.push_back({{"name", name}, {"reason", reason}});
  write_file_atomically(path, nlohmann::json{{"skipped", skipped}}.dump(1) + "\n");
}

bool SkipFilter::ReportContext(const Context& context) {
  // Google Benchmark points this reporter's streams at the output (the
  // --benchmark_out file for the file reporter) before the first call; the
  // reporter that writes must use the same streams.
  inner_.SetOutputStream(&GetOutputStream());
  inner_.SetErrorStream(&GetErrorStream());
  return inner_.ReportContext(context);
}

void SkipFilter::ReportRuns(const std::vector<Run>& runs) {
  std::vector<Run> made;
  for (const Run& run : runs) {
    if (run.error_occurred && std::string_view(run.error_message).starts_with(kSkipPrefix)) {
      log_.add(run.benchmark_name(), run.error_message.substr(kSkipPrefix.size()));
      if (on_skip_) on_skip_(run.run_name.str());
    } else
      made.push_back(run);
  }
  if (!made.empty()) inner_.ReportRuns(made);
}

}  // namespace hofem::bench
