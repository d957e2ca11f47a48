#include "report.hpp"

#include <fmt/format.h>

#include <cmath>
#include <map>
#include <stdexcept>

namespace hofem::verification {

const CheckRow& Report::check(std::string group, std::string name, double measured, double threshold, Compare compare,
                              std::string why) {
  if (why.empty())
    throw std::invalid_argument(fmt::format("verification row '{}' / '{}' has no why: every threshold needs its reason",
                                            group, name));
  CheckRow r{std::move(group), std::move(name), measured, threshold, compare, false, std::move(why)};
  r.pass = !std::isnan(measured) && (compare == Compare::AtMost ? measured <= threshold : measured >= threshold);
  rows_.push_back(std::move(r));
  return rows_.back();
}

void Report::check_rate(const std::string& group, const std::string& name, double observed, double expected,
                        double below, double above, const std::string& why) {
  if (why.empty())  // the rows' own text would hide that the bounds are unexplained
    throw std::invalid_argument(fmt::format("verification rate '{}' / '{}' has no why", group, name));
  const double lo = expected - below, hi = expected + above;
  const std::string window = fmt::format("rate window [{:g}, {:g}] around the expected {:g}", lo, hi, expected);
  check(group, name, observed, lo, Compare::AtLeast, fmt::format("{}: {}", window, why));
  // The prefix tells a reader of a failing row where to look first.
  const std::string upper = observed > hi ? "faster than theory: check the error norm (or whether the exact solution "
                                            "lies in the discrete space)"
                                          : "a rate above the window would mean a broken error norm or an exact "
                                            "solution in the discrete space";
  check(group, name, observed, hi, Compare::AtMost, fmt::format("{}; {}: {}", upper, window, why));
}

void Report::measure(std::string group, std::string name, double value, std::string what) {
  measurements_.push_back({std::move(group), std::move(name), std::move(what), value});
}

int Report::failures() const {
  int f = 0;
  for (const auto& r : rows_) f += r.pass ? 0 : 1;
  return f;
}

nlohmann::json Report::to_json() const {
  nlohmann::json rows = nlohmann::json::array();
  std::map<std::string, std::pair<int, int>> groups;
  for (const auto& r : rows_) {
    // JSON has no NaN/inf: write them as strings so the file stays valid.
    nlohmann::json measured = std::isfinite(r.measured) ? nlohmann::json(r.measured) : nlohmann::json(fmt::format("{}", r.measured));
    rows.push_back({{"group", r.group},
                    {"name", r.name},
                    {"measured", measured},
                    {"threshold", r.threshold},
                    {"compare", r.compare == Compare::AtMost ? "<=" : ">="},
                    {"pass", r.pass},
                    {"why", r.why}});
    auto& g = groups[r.group];
    ++g.first;
    g.second += r.pass ? 0 : 1;
  }
  nlohmann::json by_group = nlohmann::json::object();
  for (const auto& [name, c] : groups) by_group[name] = {{"checks", c.first}, {"failed", c.second}};
  nlohmann::json measurements = nlohmann::json::array();
  for (const auto& m : measurements_)
    measurements.push_back({{"group", m.group}, {"name", m.name}, {"value", m.value}, {"what", m.what}});
  return {{"summary", {{"checks", rows_.size()}, {"passed", static_cast<int>(rows_.size()) - failures()},
                       {"failed", failures()}, {"groups", by_group}}},
          {"rows", rows},
          {"measurements", measurements}};
}

Report Report::only(const std::string& prefix) const {
  Report out;
  for (const auto& r : rows_)
    if (r.group.starts_with(prefix)) out.rows_.push_back(r);
  for (const auto& m : measurements_)
    if (m.group.starts_with(prefix)) out.measurements_.push_back(m);
  return out;
}

std::string Report::summary_table() const {
  struct G {
    int n = 0, failed = 0;
    double worst_ratio = 0.0;  // measured/threshold for "<=" rows (closest to failing)
  };
  std::map<std::string, G> groups;
  for (const auto& r : rows_) {
    G& g = groups[r.group];
    ++g.n;
    g.failed += r.pass ? 0 : 1;
    if (r.compare == Compare::AtMost && r.threshold > 0) g.worst_ratio = std::max(g.worst_ratio, r.measured / r.threshold);
  }
  std::string out = fmt::format("{:<34} {:>7} {:>7} {:>18}\n", "group", "checks", "failed", "worst meas/thresh");
  for (const auto& [name, g] : groups)
    out += fmt::format("{:<34} {:>7} {:>7} {:>18.3g}\n", name, g.n, g.failed, g.worst_ratio);
  out += fmt::format("{:<34} {:>7} {:>7}\n", "TOTAL", rows_.size(), failures());
  return out;
}

}  // namespace hofem::verification
