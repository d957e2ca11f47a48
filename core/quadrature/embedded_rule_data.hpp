#pragma once
// The rule data files, embedded at build time (see core/CMakeLists.txt, which
// generates the definition from core/quadrature/rules/**/*.yml).
#include <span>
#include <string_view>

namespace hofem::detail {

struct EmbeddedRuleFile {
  std::string_view name;  ///< path relative to core/quadrature/rules, e.g. "triangle/WV15-5-7.yml"
  std::string_view text;
};

std::span<const EmbeddedRuleFile> embedded_rule_files();

}  // namespace hofem::detail
