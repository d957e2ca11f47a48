#include "junit_report.hpp"

#include <fmt/format.h>

#include <map>
#include <vector>

namespace hofem::verification {

std::string xml_escape(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&apos;"; break;
      default:
        // XML 1.0 allows no control characters but tab, LF and CR.
        out += (static_cast<unsigned char>(c) < 0x20 && c != '\t' && c != '\n' && c != '\r') ? '?' : c;
    }
  }
  return out;
}

namespace {

std::string failure_text(const CheckRow& r) {
  return fmt::format("measured {:.6g}, threshold {} {:.6g}: {}", r.measured, r.compare == Compare::AtMost ? "<=" : ">=",
                     r.threshold, r.why.empty() ? "(no justification recorded)" : r.why);
}

}  // namespace

std::string junit_xml(const Report& report, const std::string& suite) {
  std::map<std::string, std::vector<const CheckRow*>> groups;  // sorted by group name
  for (const CheckRow& r : report.rows()) groups[r.group].push_back(&r);
  std::string xml = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  xml += fmt::format("<testsuites name=\"{}\" tests=\"{}\" failures=\"{}\">\n", xml_escape(suite), report.rows().size(),
                     report.failures());
  for (const auto& [group, rows] : groups) {
    int failed = 0;
    for (const CheckRow* r : rows) failed += r->pass ? 0 : 1;
    xml += fmt::format("  <testsuite name=\"{}\" tests=\"{}\" failures=\"{}\">\n", xml_escape(group), rows.size(), failed);
    for (const CheckRow* r : rows) {
      xml += fmt::format("    <testcase classname=\"{}\" name=\"{}\"", xml_escape(group), xml_escape(r->name));
      if (r->pass) {
        xml += "/>\n";
        continue;
      }
      const std::string text = xml_escape(failure_text(*r));
      xml += fmt::format(">\n      <failure message=\"{}\">{}</failure>\n    </testcase>\n", text, text);
    }
    xml += "  </testsuite>\n";
  }
  xml += "</testsuites>\n";
  return xml;
}

}  // namespace hofem::verification
