#pragma once
// The verification report as JUnit XML, the test-result format CI systems
// (GitLab, Jenkins, GitHub test reporters) read natively: one <testsuite> per
// group, one <testcase> per check; a failed check carries a <failure> whose
// text gives the measured value, the threshold and why the threshold is what
// it is. Measurements without a verdict are not test cases.
#include "report.hpp"

#include <string>

namespace hofem::verification {

/// The XML document; `suite` names the whole run ("hofem.verify").
std::string junit_xml(const Report& report, const std::string& suite);

/// `text` with &, <, >, " and ' escaped, and characters XML 1.0 cannot hold
/// (control characters other than tab and newlines) replaced by '?'.
std::string xml_escape(const std::string& text);

}  // namespace hofem::verification
