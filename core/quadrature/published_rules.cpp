#include "quadrature/published_rules.hpp"

#include "quadrature/embedded_rule_data.hpp"

#include <Eigen/QR>
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <initializer_list>
#include <map>
#include <optional>

namespace hofem {

namespace {

using Real = long double;  // expansion and weight solve in extended precision
using Bary = std::vector<Real>;

struct RawRule {
  std::string reference;
  int dim = -1;
  int degree = -1;
  std::vector<int> orbits;
  std::vector<Real> positions;
  std::vector<Real> weights;
  std::string citation;
  std::string quality;
};

[[noreturn]] void fail(std::string_view origin, int line, const std::string& what) {
  throw RuleFormatError(fmt::format("{}:{}: {}", origin, line, what));
}

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t' || s.front() == '\r')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) s.remove_suffix(1);
  return s;
}

std::string_view unquote(std::string_view s) {
  if (s.size() >= 2 && (s.front() == '\'' || s.front() == '"') && s.back() == s.front())
    return s.substr(1, s.size() - 2);
  return s;
}

Real parse_real(std::string_view text, std::string_view origin, int line) {
  const std::string s(unquote(trim(text)));
  if (s.empty()) fail(origin, line, "expected a number, found nothing");
  errno = 0;
  char* end = nullptr;
  const Real v = std::strtold(s.c_str(), &end);
  if (end != s.c_str() + s.size() || errno == ERANGE || !std::isfinite(static_cast<double>(v)))
    fail(origin, line, fmt::format("'{}' is not a finite number", s));
  return v;
}

int parse_int(std::string_view text, std::string_view origin, int line) {
  const std::string s(trim(text));
  char* end = nullptr;
  errno = 0;
  const long v = std::strtol(s.c_str(), &end, 10);
  if (s.empty() || end != s.c_str() + s.size() || errno == ERANGE || v < 0 || v > 100000)
    fail(origin, line, fmt::format("'{}' is not a non-negative integer", s));
  return static_cast<int>(v);
}

RawRule parse_raw(std::string_view text, std::string_view origin) {
  RawRule r;
  std::vector<Real>* list = nullptr;  // where list items go: r.positions, r.weights or nowhere
  bool saw_positions = false, saw_orbits = false;
  int line_no = 0;
  size_t pos = 0;
  while (pos <= text.size()) {
    size_t eol = text.find('\n', pos);
    if (eol == std::string_view::npos) eol = text.size();
    const std::string_view raw = text.substr(pos, eol - pos);
    pos = eol + 1;
    ++line_no;
    const std::string_view line = trim(raw);
    if (line.empty()) continue;
    if (line.front() == '#') {
      if (line.starts_with("# Source:")) r.citation = std::string(trim(line.substr(9)));
      continue;
    }
    if (line.front() == '-') {
      if (!list) fail(origin, line_no, "list item outside 'positions:' or 'weights:'");
      list->push_back(parse_real(line.substr(1), origin, line_no));
      continue;
    }
    const size_t colon = line.find(':');
    if (colon == std::string_view::npos) fail(origin, line_no, fmt::format("expected 'key: value', found '{}'", line));
    const std::string_view key = trim(line.substr(0, colon));
    const std::string_view value = trim(line.substr(colon + 1));
    list = nullptr;
    if (key == "reference") {
      r.reference = std::string(unquote(value));
    } else if (key == "region") {
      if (unquote(value) != "simplex") fail(origin, line_no, fmt::format("region '{}' is not supported (expected simplex)", value));
    } else if (key == "dim") {
      r.dim = parse_int(value, origin, line_no);
      if (r.dim != 2 && r.dim != 3) fail(origin, line_no, fmt::format("dim must be 2 or 3, got {}", r.dim));
    } else if (key == "degree") {
      r.degree = parse_int(value, origin, line_no);
    } else if (key == "quality") {
      r.quality = std::string(unquote(value));  // kept to be verified, never trusted
    } else if (key == "accuracy") {
      // Published label; hofem measures exactness itself.
    } else if (key == "orbits") {
      if (value.size() < 2 || value.front() != '[' || value.back() != ']')
        fail(origin, line_no, "orbits must be a list like [0, 2, 1]");
      std::string_view body = value.substr(1, value.size() - 2);
      while (!trim(body).empty()) {
        const size_t comma = body.find(',');
        r.orbits.push_back(parse_int(body.substr(0, comma), origin, line_no));
        if (comma == std::string_view::npos) break;
        body.remove_prefix(comma + 1);
      }
      saw_orbits = true;
    } else if (key == "positions") {
      if (!value.empty()) fail(origin, line_no, "positions: the list must start on the next line");
      list = &r.positions;
      saw_positions = true;
    } else if (key == "weights") {
      if (!value.empty()) fail(origin, line_no, "weights: the list must start on the next line");
      list = &r.weights;
    } else {
      fail(origin, line_no, fmt::format("unknown key '{}' (valid: reference, region, dim, degree, quality, accuracy, orbits, positions, weights)", key));
    }
  }
  if (r.dim < 0) fail(origin, line_no, "missing key 'dim'");
  if (r.degree < 0) fail(origin, line_no, "missing key 'degree'");
  if (!saw_orbits) fail(origin, line_no, "missing key 'orbits'");
  if (!saw_positions) fail(origin, line_no, "missing key 'positions'");
  return r;
}

// A symmetry orbit type: number of parameters and the expansion into barycentric points.
struct OrbitType {
  const char* name;
  int args;
  std::function<std::vector<Bary>(const Real*)> expand;
};

// The points of a triangle orbit with parameters (a, b): the barycentric triple
// (a, b, 1 - a - b) under each of the given permutations.
std::vector<Bary> permuted(const Real* p, std::initializer_list<std::array<int, 3>> permutations) {
  const Real v[3] = {p[0], p[1], 1 - p[0] - p[1]};
  std::vector<Bary> out;
  for (const auto& s : permutations) out.push_back({v[s[0]], v[s[1]], v[s[2]]});
  return out;
}

const std::vector<OrbitType>& triangle_orbits() {
  static const std::vector<OrbitType> types = {
      {"S3", 0, [](const Real*) { return std::vector<Bary>{{Real(1) / 3, Real(1) / 3, Real(1) / 3}}; }},
      {"S21", 1,
       [](const Real* p) {
         const Real a = p[0], c = 1 - 2 * a;
         return std::vector<Bary>{{a, a, c}, {a, c, a}, {c, a, a}};
       }},
      {"S111", 2,
       [](const Real* p) { return permuted(p, {{0, 1, 2}, {0, 2, 1}, {2, 0, 1}, {1, 0, 2}, {1, 2, 0}, {2, 1, 0}}); }},
      {"A3", 2, [](const Real* p) { return permuted(p, {{0, 1, 2}, {1, 2, 0}, {2, 0, 1}}); }},
      {"M12", 2, [](const Real* p) { return permuted(p, {{0, 1, 2}, {1, 0, 2}}); }},
      {"M13", 2, [](const Real* p) { return permuted(p, {{0, 1, 2}, {2, 1, 0}}); }},
      {"M23", 2, [](const Real* p) { return permuted(p, {{0, 1, 2}, {0, 2, 1}}); }},
      {"I", 3, [](const Real* p) { return std::vector<Bary>{{p[0], p[1], p[2]}}; }},
  };
  return types;
}

const std::vector<OrbitType>& tetrahedron_orbits() {
  static const std::vector<OrbitType> types = {
      {"S4", 0, [](const Real*) { return std::vector<Bary>{{Real(0.25), Real(0.25), Real(0.25), Real(0.25)}}; }},
      {"S31", 1,
       [](const Real* p) {
         const Real a = p[0], d = 1 - 3 * a;
         return std::vector<Bary>{{a, a, a, d}, {a, a, d, a}, {a, d, a, a}, {d, a, a, a}};
       }},
      {"S22", 1,
       [](const Real* p) {
         const Real a = p[0], b = Real(0.5) - a;
         return std::vector<Bary>{{a, a, b, b}, {a, b, a, b}, {b, a, a, b}, {a, b, b, a}, {b, a, b, a}, {b, b, a, a}};
       }},
      {"S211", 2,
       [](const Real* p) {
         const Real a = p[0], b = p[1], c = 1 - 2 * a - b;
         return std::vector<Bary>{{a, a, b, c}, {a, b, a, c}, {b, a, a, c}, {a, a, c, b}, {a, c, a, b}, {c, a, a, b},
                                  {a, b, c, a}, {b, a, c, a}, {a, c, b, a}, {b, c, a, a}, {c, a, b, a}, {c, b, a, a}};
       }},
      {"S1111", 3,
       [](const Real* p) {
         const std::array<Real, 4> v{p[0], p[1], p[2], 1 - p[0] - p[1] - p[2]};
         std::array<int, 4> idx{0, 1, 2, 3};
         std::vector<Bary> out;
         do out.push_back({v[idx[0]], v[idx[1]], v[idx[2]], v[idx[3]]});
         while (std::next_permutation(idx.begin(), idx.end()));
         return out;
       }},
  };
  return types;
}

// Exact monomial integral over the unit simplex: a! b! c! / (a + b + c + d)!.
Real simplex_monomial_integral(const std::array<int, 3>& e, int d) {
  Real num = 1;
  int total = 0;
  for (int i = 0; i < d; ++i) {
    for (int k = 2; k <= e[i]; ++k) num *= k;
    total += e[i];
  }
  Real den = 1;
  for (int k = 2; k <= total + d; ++k) den *= k;
  return num / den;
}

// Orbit weights by least squares on the moment equations of all monomials up to
// the rule's degree (consistent system: the residual is at rounding level, and a
// backward-stable QR keeps it there however the monomial matrix is conditioned).
std::vector<Real> solve_orbit_weights(const std::vector<std::vector<Bary>>& orbit_points, int dim, int degree) {
  std::vector<std::array<int, 3>> exps;
  for (int a = 0; a <= degree; ++a)
    for (int b = 0; a + b <= degree; ++b)
      if (dim == 2) exps.push_back({a, b, 0});
      else
        for (int c = 0; a + b + c <= degree; ++c) exps.push_back({a, b, c});
  using Mat = Eigen::Matrix<Real, Eigen::Dynamic, Eigen::Dynamic>;
  using Vec = Eigen::Matrix<Real, Eigen::Dynamic, 1>;
  Mat A = Mat::Zero(static_cast<Eigen::Index>(exps.size()), static_cast<Eigen::Index>(orbit_points.size()));
  Vec b(static_cast<Eigen::Index>(exps.size()));
  for (size_t m = 0; m < exps.size(); ++m) {
    b[m] = simplex_monomial_integral(exps[m], dim);
    for (size_t o = 0; o < orbit_points.size(); ++o)
      for (const Bary& p : orbit_points[o]) {
        Real v = 1;
        for (int i = 0; i < dim; ++i)
          for (int k = 0; k < exps[m][i]; ++k) v *= p[i + 1];
        A(m, o) += v;
      }
  }
  const Vec w = A.colPivHouseholderQr().solve(b);
  return std::vector<Real>(w.data(), w.data() + w.size());
}

}  // namespace

QuadratureRule parse_published_rule(std::string_view text, std::string_view origin) {
  const RawRule r = parse_raw(text, origin);
  const CellType cell = r.dim == 2 ? CellType::Triangle : CellType::Tetrahedron;
  const auto& types = r.dim == 2 ? triangle_orbits() : tetrahedron_orbits();
  if (r.orbits.size() != types.size())
    fail(origin, 0, fmt::format("orbits has {} entries, expected {} for dim {} ({})", r.orbits.size(), types.size(), r.dim,
                                r.dim == 2 ? "S3, S21, S111, A3, M12, M13, M23, I" : "S4, S31, S22, S211, S1111"));
  std::vector<std::vector<Bary>> orbit_points;
  size_t j = 0;
  for (size_t t = 0; t < types.size(); ++t)
    for (int k = 0; k < r.orbits[t]; ++k) {
      if (j + types[t].args > r.positions.size())
        fail(origin, 0, fmt::format("orbits need more positions than the {} given", r.positions.size()));
      orbit_points.push_back(types[t].expand(r.positions.data() + j));
      j += types[t].args;
    }
  if (j != r.positions.size())
    fail(origin, 0, fmt::format("orbits use {} positions but {} are given", j, r.positions.size()));
  std::vector<Real> w = r.weights;
  std::string weight_note;
  if (w.empty()) {
    w = solve_orbit_weights(orbit_points, r.dim, r.degree);
    weight_note = "; weights solved from the moment equations";
  } else {
    if (w.size() != orbit_points.size())
      fail(origin, 0, fmt::format("{} weights given for {} orbits", w.size(), orbit_points.size()));
    const Real vol = r.dim == 2 ? Real(0.5) : Real(1) / 6;
    for (Real& x : w) x *= vol;  // published normalisation: sum = 1
  }
  QuadratureRule q;
  q.cell = cell;
  q.degree = r.degree;
  q.family = RuleFamily::Published;
  q.claimed_quality = r.quality;
  {
    std::string_view stem = origin.substr(origin.find_last_of('/') + 1);  // npos + 1 == 0
    if (stem.ends_with(".yml")) stem.remove_suffix(4);
    q.id = std::string(stem);
  }
  q.source = fmt::format("{} ({}){}", r.reference, r.citation.empty() ? std::string(origin) : r.citation, weight_note);
  int n = 0;
  for (const auto& o : orbit_points) n += static_cast<int>(o.size());
  q.points.resize(r.dim, n);
  q.weights.resize(n);
  int k = 0;
  for (size_t o = 0; o < orbit_points.size(); ++o)
    for (const Bary& p : orbit_points[o]) {
      for (int i = 0; i < r.dim; ++i) q.points(i, k) = static_cast<double>(p[i + 1]);
      q.weights[k] = static_cast<double>(w[o]);
      ++k;
    }
  return q;
}

std::vector<QuadratureRule> published_rules(CellType cell) {
  std::vector<QuadratureRule> out;
  const std::string_view prefix = cell == CellType::Triangle ? "triangle/" : cell == CellType::Tetrahedron ? "tetrahedron/" : "";
  if (prefix.empty()) return out;
  for (const detail::EmbeddedRuleFile& f : detail::embedded_rule_files())
    if (f.name.starts_with(prefix)) out.push_back(parse_published_rule(f.text, f.name));
  return out;
}

}  // namespace hofem
