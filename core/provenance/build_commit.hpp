#pragma once
// The commit the library was built from, in a source generated at every build
// (cmake/BuildInfo.cmake): only that file recompiles after a new commit.
#include <string_view>

namespace hofem::detail {

/// `git rev-parse HEAD` of the source tree at build time, or "unknown".
std::string_view build_commit();
/// Whether tracked files differed from that commit.
bool build_dirty();

}  // namespace hofem::detail
