// hofem-verify: the verification suite behind `hofem verify` (cli/main.cpp
// hands its arguments over), writing reports/verification.json and, when the
// manufactured-solution study runs, its tidy table beside it
// (reports/convergence.csv and .json; --convergence-table PREFIX moves them).
// Its options are parsed by the same command-line code as every other subcommand.
#include "command_line.hpp"
#include "io/atomic_file.hpp"
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

// Creates the directory a file is written into, if missing.
void ensure_parent_directory(const std::string& path) {
  if (const std::filesystem::path p(path); p.has_parent_path()) std::filesystem::create_directories(p.parent_path());
}

// The convergence table's files: PREFIX.csv and PREFIX.json, PREFIX by default
// "convergence" in the directory of the report (--out).
void write_convergence_table(const hofem::ConvergenceTable& table, const hofem::cli::VerifyOptions& o) {
  const std::string prefix = !o.convergence_table.empty()
                                 ? o.convergence_table
                                 : (std::filesystem::path(o.out).parent_path() / "convergence").string();
  ensure_parent_directory(prefix + ".csv");
  hofem::write_file_atomically(prefix + ".csv", table.to_csv());
  hofem::write_file_atomically(prefix + ".json", table.to_json().dump(1) + "\n");
  fmt::print("convergence table: {} rows -> {}.csv, {}.json\n", table.rows().size(), prefix, prefix);
}

int run_verify(const hofem::cli::VerifyOptions& o) {
  using namespace hofem::verification;
  hofem::ConvergenceTable table;
  SuiteOptions options{o.convergence};
  options.convergence_table = &table;
  Report report = run_all_checks(options);
  // --group: the file holds that group's rows, measurements and summary only.
  const nlohmann::json j = o.group.empty() ? report.to_json() : report.only(o.group).to_json();
  ensure_parent_directory(o.out);
  hofem::write_file_atomically(o.out, j.dump(1) + "\n");  // complete or absent, never truncated
  if (o.convergence != "none") write_convergence_table(table, o);
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
