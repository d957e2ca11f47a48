// hofem-verify: the verification suite behind `hofem verify` (cli/main.cpp
// hands its arguments over), writing reports/verification.json. Its options
// are parsed by the same command-line code as every other subcommand.
#include "command_line.hpp"
#include "io/atomic_file.hpp"
#include "run_verification.hpp"

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include <cstdio>
#include <exception>
#include <filesystem>
#include <string>
#include <vector>

namespace {

int run_verify(const hofem::cli::VerifyOptions& o) {
  using namespace hofem::verification;
  Report report = run_all_checks({o.convergence});
  // --group: the file holds that group's rows, measurements and summary only.
  const nlohmann::json j = o.group.empty() ? report.to_json() : report.only(o.group).to_json();
  if (const std::filesystem::path p(o.out); p.has_parent_path()) std::filesystem::create_directories(p.parent_path());
  hofem::write_file_atomically(o.out, j.dump(1) + "\n");  // complete or absent, never truncated
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
