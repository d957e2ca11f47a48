#include "quadrature/rule_library.hpp"

#include "quadrature/gauss_rules.hpp"
#include "quadrature/hammer_rules.hpp"
#include "quadrature/published_rules.hpp"

#include <fmt/format.h>

#include <map>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <utility>

namespace hofem {

namespace {

std::vector<QuadratureRule> load_tabulated(CellType cell) {
  std::vector<QuadratureRule> rules;
  if (cell != CellType::Triangle && cell != CellType::Tetrahedron) return rules;
  for (QuadratureRule& r : published_rules(cell)) rules.push_back(std::move(r));
  for (QuadratureRule& r : hammer_rules(cell)) rules.push_back(std::move(r));
  return rules;
}

// Orders candidates: positive-interior first, then fewer points, then symmetric
// tabulated rules (published data, then Hammer) before collapsed Gauss rules
// (a symmetric rule has no preferred vertex), then the larger distance of the
// points from the boundary (a rule with points 1e-9 from a vertex is interior in
// name only), then higher degree.
bool better(const QuadratureRule& a, const QuadratureRule& b) {
  if (a.positive_interior() != b.positive_interior()) return a.positive_interior();
  if (a.size() != b.size()) return a.size() < b.size();
  if (a.family != b.family) return static_cast<int>(a.family) > static_cast<int>(b.family);
  if (const double ma = a.min_interior_margin(), mb = b.min_interior_margin(); ma != mb) return ma > mb;
  return a.degree > b.degree;
}

class RuleCache {
 public:
  const std::vector<QuadratureRule>& tabulated(CellType cell) {
    std::call_once(once_[static_cast<int>(cell)], [&] { tab_[static_cast<int>(cell)] = load_tabulated(cell); });
    return tab_[static_cast<int>(cell)];
  }

  const QuadratureRule& best(CellType cell, int degree) {
    if (degree < 0) throw std::invalid_argument(fmt::format("quadrature degree must be >= 0, got {}", degree));
    const auto& tab = tabulated(cell);  // outside the lock: call_once synchronises itself
    std::lock_guard<std::mutex> lock(mutex_);
    auto key = std::make_pair(static_cast<int>(cell), degree);
    if (auto it = best_.find(key); it != best_.end()) return *it->second;
    auto gauss = std::make_unique<QuadratureRule>(gauss_rule_for_degree(cell, degree));
    const QuadratureRule* pick = gauss.get();
    for (const QuadratureRule& r : tab)
      if (r.degree >= degree && better(r, *pick)) pick = &r;
    if (pick == gauss.get()) {
      owned_.push_back(std::move(gauss));
      pick = owned_.back().get();
    }
    best_[key] = pick;
    return *pick;
  }

 private:
  std::once_flag once_[5];
  std::vector<QuadratureRule> tab_[5];
  std::mutex mutex_;
  std::map<std::pair<int, int>, const QuadratureRule*> best_;
  std::vector<std::unique_ptr<QuadratureRule>> owned_;
};

RuleCache& cache() {
  static RuleCache c;
  return c;
}

}  // namespace

const QuadratureRule& quadrature_rule(CellType cell, int degree) { return cache().best(cell, degree); }

const std::vector<QuadratureRule>& tabulated_rules(CellType cell) { return cache().tabulated(cell); }

int max_tabulated_degree(CellType cell) {
  int d = 0;
  for (const QuadratureRule& r : tabulated_rules(cell)) d = std::max(d, r.degree);
  return d;
}

}  // namespace hofem
