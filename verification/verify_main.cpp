// hofem-verify: the verification suite behind `hofem verify` (cli/main.cpp
// hands its arguments over), writing reports/verification.json and, when the
// manufactured-solution study runs, its tidy table beside it
// (reports/convergence.csv and .json; --convergence-table PREFIX moves them).
// Its options are parsed by the same command-line code as every other subcommand.
#include "command_line.hpp"
#include "io/atomic_file.hpp"
#include "junit_report.hpp"
#include "provenance/provenance.hpp"
#include "run_verification.hpp"
#include "study/convergence_table.hpp"

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include <cstdio>
#include <exception>
#include <filesystem>
#include <string>
#include <vector>

namespace {

void write_file(const std::string& path, const std::string& text) {
  if (const std::filesystem::path p(path); p.has_parent_path()) std::filesystem::create_directories(p.parent_path());
  hofem::write_file_atomically(path, text);  // complete or absent, never truncated
}

// `hofem verify --list`: one line per family, "id label groups...", the order
// the suite runs them (ctest's verify.<id> tests are checked against it).
int list_families() {
  for (const auto& f : hofem::verification::check_families()) {
    fmt::print("{} {}", f.id, f.label);
    for (const auto& g : f.groups) fmt::print(" {}", g);
    fmt::print("\n");
  }
  return 0;
}

// The convergence table's files: PREFIX.csv and PREFIX.json, PREFIX by default
// "convergence" in the directory of the report (--out).
void write_convergence_table(const hofem::ConvergenceTable& table, const hofem::cli::VerifyOptions& o) {
  const std::string prefix = !o.convergence_table.empty()
                                 ? o.convergence_table
                                 : (std::filesystem::path(o.out).parent_path() / "convergence").string();
  write_file(prefix + ".csv", table.to_csv());
  write_file(prefix + ".json", table.to_json().dump(1) + "\n");
  if (!o.quiet) fmt::print("convergence table: {} rows -> {}.csv, {}.json\n", table.rows().size(), prefix, prefix);
}

int run_verify(const hofem::cli::VerifyOptions& o) {
  using namespace hofem::verification;
  if (o.list) return list_families();
  hofem::ConvergenceTable table;
  const SuiteOptions options{
      .convergence = o.convergence, .group = o.group, .progress = true, .convergence_table = &table};
  if (selected_families(options).empty()) {
    fmt::print(stderr, "hofem: error: {}\n", no_families_message(options));
    return 2;
  }
  Report report = run_checks(options);
  // --group: the file holds that prefix's rows, measurements and summary only.
  if (!o.group.empty()) report = report.only(o.group);
  nlohmann::json j = report.to_json();
  j["context"] = hofem::provenance_context(o.convergence);
  write_file(o.out, j.dump(1) + "\n");
  if (!o.junit.empty()) write_file(o.junit, junit_xml(report, "hofem.verify"));
  if (!table.rows().empty()) write_convergence_table(table, o);
  if (!o.quiet) {
    fmt::print("{}", report.summary_table());
    for (const auto& r : report.rows())
      if (!r.pass)
        fmt::print("FAILED {} | {}: measured {:.3e}, threshold {} {:.3e}\n", r.group, r.name, r.measured,
                   r.compare == Compare::AtMost ? "<=" : ">=", r.threshold);
  }
  fmt::print("verification: {} checks, {} failed -> {}\n", report.rows().size(), report.failures(), o.out);
  return report.failures() == 0 ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  // Parsed as `hofem verify ARGS`, so the options and messages are the CLI's.
  std::vector<char*> args{argv[0], const_cast<char*>("verify")};
  for (int i = 1; i < argc; ++i) args.push_back(argv[i]);
  hofem::cli::CommandLine cl;
  if (const int status = hofem::cli::parse_command_line(static_cast<int>(args.size()), args.data(), cl, stdout, stderr);
      status >= 0)
    return status;
  const hofem::cli::VerifyOptions& o = cl.verify;
  if (o.convergence != "none" && o.convergence != "ci" && o.convergence != "full") {
    fmt::print(stderr, "hofem: error: --convergence: unknown preset '{}' (valid: none, ci, full)\n", o.convergence);
    return 2;
  }
  try {
    return run_verify(o);
  } catch (const std::exception& e) {
    fmt::print(stderr, "hofem: error: {}\n", e.what());
    return 1;
  }
}
