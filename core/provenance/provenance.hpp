#pragma once
// Where a result came from: hofem's version and commit, how it was built, when
// and on what machine it ran. Every JSON output (verification.json, a scene's
// stats.json, study.json, the benchmarks' context) carries provenance_context()
// as "context", so a number can be traced to the code and machine that made it.
#include <nlohmann/json.hpp>

#include <string>
#include <string_view>

namespace hofem {

/// Version of the layout of hofem's JSON outputs: raised when a field changes
/// meaning or disappears (adding a field does not raise it).
inline constexpr int kOutputSchemaVersion = 1;

/// hofem's version (CMakeLists.txt's project version), e.g. "0.1.0".
std::string_view hofem_version();

/// `hofem --version`: version, commit (with "-dirty"), build type and compiler.
std::string version_text();

/// {"schema_version", "hofem_version", "commit", "dirty", "date" (UTC, ISO 8601),
///  "build_type", "compiler", "flags", "preset", "hostname", "cpu", "cores",
///  "threads"}: "preset" is what the caller ran ("ci", "full", "quick", a scene
/// name...; empty if it has none), "threads" OpenMP's maximum.
nlohmann::json provenance_context(std::string_view preset = {});

}  // namespace hofem
