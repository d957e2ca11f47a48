#include "symbolic_material_checks.hpp"

#include "material/material.hpp"
#include "material_checks.hpp"
#include "symbolic_material.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace hofem::verification {

namespace {

constexpr const char* kGroup = "material.symbolic";

struct Differences {
  double energy = 0.0, stress = 0.0, tangent = 0.0;
};

// Largest differences over the samples, each relative to the larger of the
// reference's magnitude and the material's scale mu + |lambda| (so a quantity
// that vanishes, such as P at F = R, is judged against the stiffness).
Differences differences(const Material& m, const SymbolicMaterial& s, const std::vector<Mat3>& samples) {
  const double scale = m.lame().mu + std::fabs(m.lame().lambda);
  Differences d;
  for (const Mat3& F : samples) {
    Mat3 P;
    Mat9 A;
    const double psi = m.evaluate(F, &P, &A);
    const Mat3 Ps = s.stress(F);
    const Mat9 As = s.tangent(F);
    const double psi_s = s.energy(F);
    d.energy = std::max(d.energy, std::fabs(psi - psi_s) / std::max(std::fabs(psi_s), scale));
    d.stress = std::max(d.stress, (P - Ps).cwiseAbs().maxCoeff() / std::max(Ps.cwiseAbs().maxCoeff(), scale));
    d.tangent = std::max(d.tangent, (A - As).cwiseAbs().maxCoeff() / std::max(As.cwiseAbs().maxCoeff(), scale));
  }
  return d;
}

// tangent_fd_scale: the reference tangent's own error over 1e-12, 1 where it is
// sympy's closed form (symbolic_material.hpp).
void add_rows(Report& report, const std::string& label, const std::string& kind, const Differences& d, double det_scale,
              double tangent_fd_scale) {
  // Both sides are closed forms of the same law, evaluated in double (core) and
  // long double (sympy's): they differ by core's round-off, a few ulps of each
  // term amplified by the conditioning of F. Regular F: 1e-12 (~5000 eps); the
  // near-inverted samples (det F down to 0.005) carry 1/J and cof(F)/J terms,
  // so the bound scales by 1/min det F (200x). The corotated tangent is the
  // exception on the reference side: a five-point difference in long double,
  // ~1e-11 where two stretches of opposite sign sum to 0.1 (the inverted
  // samples), so that one row gets 1e-10 (measured 3.9e-12).
  const double tol = 1e-12 * det_scale, tangent_tol = tol * tangent_fd_scale;
  const auto why = [&](double t) {
    return fmt::format("max relative difference against the law sympy derived from psi (verification/symbolic); "
                       "{:.0e}: core's round-off in double, x {:.0f} for 1/det F{}",
                       t, det_scale, t > tol ? ", x 100 for the reference tangent's finite difference" : "");
  };
  report.check(kGroup, fmt::format("{} {}: psi", label, kind), d.energy, tol, Compare::AtMost, why(tol));
  report.check(kGroup, fmt::format("{} {}: P", label, kind), d.stress, tol, Compare::AtMost, why(tol));
  report.check(kGroup, fmt::format("{} {}: dP/dF", label, kind), d.tangent, tangent_tol, Compare::AtMost,
               why(tangent_tol));
}

}  // namespace

void add_symbolic_material_checks(Report& report) {
  const std::vector<std::string> core_names = material_names();
  const std::vector<std::string> derived = symbolic_material_names();
  int missing = 0;
  for (const std::string& n : core_names) missing += std::count(derived.begin(), derived.end(), n) == 0;
  for (const std::string& n : derived) missing += std::count(core_names.begin(), core_names.end(), n) == 0;
  report.check(kGroup, "materials without a symbolic law (or laws without a material)", missing, 0,
               Compare::AtMost, "every name of material_names() has its law in derive_material_laws.py and back");
  const DeformationSamples samples = deformation_samples();
  for (double nu : {0.3, 0.48}) {
    const LameParameters lame = LameParameters::from_young_poisson(1e6, nu);
    for (const std::string& n : core_names) {
      if (std::count(derived.begin(), derived.end(), n) == 0) continue;
      const auto m = make_material(n, lame);
      const SymbolicMaterial s(n, lame.mu, lame.lambda);
      const std::string label = fmt::format("{} E=1e6 nu={}", n, nu);
      add_rows(report, label, "regular", differences(*m, s, samples.regular), 1.0, 1.0);
      add_rows(report, label, "near-inverted", differences(*m, s, samples.near_inverted), 200.0, 1.0);
      bool defined = true;
      for (const Mat3& F : samples.inverted) defined = defined && m->defined_at(F);
      if (defined)
        add_rows(report, label, "inverted", differences(*m, s, samples.inverted), 1.0, n == "corotated" ? 100.0 : 1.0);
    }
  }
}

}  // namespace hofem::verification
