#include "material_checks.hpp"

#include "symbolic_material_checks.hpp"

#include "material/corotated.hpp"
#include "material/linear_elastic.hpp"
#include "material/stable_neo_hookean.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <Eigen/LU>  // determinant
#include <Eigen/SVD>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <random>
#include <string>

namespace hofem::verification {

namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();

// ---------------------------------------------------------------------------
// Finite-difference step and tolerance.
//
// Step: h = kFdStep * l(F), l(F) = fd_length_scale(F) (smallest singular value; for
// inverted F also the distance to the corotated branch switch). Near-singular F
// make the derivatives vary on the scale l(F), so a step relative to it keeps the
// truncation error uniform across the samples.
//
// Error model for a central difference of a function g with values of size |g|
// (relative to the scale of the derivative, |g|/l): truncation h^2/6 |g'''| ~
// c^2/6 K3 and rounding eps |g| / h ~ eps/c K0, with c = h / l and K3, K0 the
// dimensionless ratios l^3 |g'''| / |g|, |g| / (l |g'|). The sum is smallest at
// c ~ eps^(1/3) ~ 6e-6; we take c = 1e-5 (truncation 1.7e-11 K3, rounding 2.2e-11 K0).
// The ratios K are O(1) at regular F and grow to ~1e2 at the near-inverted and
// inverted samples (psi is then dominated by a volume term much larger than the
// stress along the probed direction), so the predicted error is <~ 1e-8 (measured
// worst: ~1e-8, corotated near inversion). Tolerance 1e-6 leaves ~100x over that,
// while a wrong coefficient or a missing term in P or dP/dF (every term carries mu
// or lambda, i.e. the scale) shows up at >~ 1e-2, and even a 1e-4 relative error
// in one entry of P is caught (see material.fd_sensitivity).
constexpr double kFdStep = 1e-5;
constexpr double kFdTol = 1e-6;

// Major symmetry: the entries are sums of <= 4 terms of size <~ max |dP/dF|, each
// with a handful of roundings, so the two triangles differ by <~ 20 eps of
// max |dP/dF|. Corotated's tangent is not symmetric term by term (R [w]x with w
// through (tr S I - S)^{-1}), but the rounding of that term is relative to its own
// size, which is bounded by max |dP/dF| too. 1e-14 ~ 45 eps.
constexpr double kSymTol = 1e-14;

// Rotation invariance psi(QF) = psi(F): Q carries ~eps of rounding (|Q^T Q - I| ~ eps)
// and psi is a sum of terms of size <= (mu + |lambda|) ||F||^4 ~ 60 (mu + |lambda|) for
// the samples; relative to max(|psi|, mu + |lambda|) that is <~ 100 eps ~ 2e-14.
// The same holds for P(QF) = Q P(F). 1e-13 ~ 450 eps.
constexpr double kInvarianceTol = 1e-13;

// F = I: P(I) and dP/dF(I) - C_linear are sums of a few terms of size <= mu + |lambda|
// (Stable Neo-Hookean: lambda (1 - alpha) cancels 3 mu / 4), so rounding is a few eps.
constexpr double kRestTol = 16 * kEps;

class Rng {
 public:
  explicit Rng(std::uint64_t seed) : g_(seed) {}
  /// Uniform in [a, b) from the top 53 bits (independent of the standard library's distributions).
  double uniform(double a, double b) { return a + (b - a) * (static_cast<double>(g_() >> 11) * 0x1.0p-53); }
  /// Uniform random rotation (Shoemake's unit quaternion from three uniforms).
  Mat3 rotation() {
    const double u1 = uniform(0, 1), u2 = uniform(0, 1), u3 = uniform(0, 1);
    const double a = std::sqrt(1 - u1), b = std::sqrt(u1), t2 = 2 * std::numbers::pi * u2, t3 = 2 * std::numbers::pi * u3;
    return Eigen::Quaterniond(b * std::cos(t3), a * std::sin(t2), a * std::cos(t2), b * std::sin(t3)).toRotationMatrix();
  }

 private:
  std::mt19937_64 g_;
};

double scale_of(const Material& m) { return m.lame().mu + std::fabs(m.lame().lambda); }

template <typename M>
double max_abs(const M& A) {
  return A.cwiseAbs().maxCoeff();
}

bool all_finite(const auto& A) { return A.allFinite(); }

std::string fmt_nu(double nu) { return fmt::format("nu={}", nu); }

}  // namespace

double fd_length_scale(const Mat3& F) {
  const Eigen::JacobiSVD<Mat3, Eigen::NoQRPreconditioner> svd(F);
  const Eigen::Vector3d s = svd.singularValues();
  if (F.determinant() >= 0.0) return s[2];
  // Signed values (s0, s1, -s2): the pair sums are s0 + s1, s0 - s2, s1 - s2.
  return std::min(s[2], s[1] - s[2]);
}

double stress_fd_error(const Material& material, const Mat3& F, double h) {
  const Mat3 P = material.stress(F);
  double err = 0.0;
  for (int b = 0; b < 9; ++b) {
    Mat3 Fp = F, Fm = F;
    Fp.data()[b] += h;
    Fm.data()[b] -= h;
    // The step actually taken (F + h is rounded), so it adds no error of its own.
    const double step = Fp.data()[b] - Fm.data()[b];
    const double fd = (material.energy(Fp) - material.energy(Fm)) / step;
    err = std::max(err, std::fabs(fd - P.data()[b]));
  }
  return err / std::max(max_abs(P), scale_of(material));
}

double tangent_fd_error(const Material& material, const Mat3& F, double h, const Mat9& tangent) {
  double err = 0.0;
  for (int b = 0; b < 9; ++b) {
    Mat3 Fp = F, Fm = F;
    Fp.data()[b] += h;
    Fm.data()[b] -= h;
    const double step = Fp.data()[b] - Fm.data()[b];
    const Mat3 dP = (material.stress(Fp) - material.stress(Fm)) / step;
    for (int a = 0; a < 9; ++a) err = std::max(err, std::fabs(dP.data()[a] - tangent(a, b)));
  }
  return err / std::max(max_abs(tangent), scale_of(material));
}

double tangent_fd_error(const Material& material, const Mat3& F, double h) {
  return tangent_fd_error(material, F, h, material.stress_derivative(F));
}

double tangent_asymmetry(const Material& material, const Mat3& F) {
  const Mat9 A = material.stress_derivative(F);
  return max_abs(Mat9(A - A.transpose())) / max_abs(A);
}

DeformationSamples deformation_samples(int regular, int near_inverted, int inverted) {
  Rng rng(0x6d61746572696131ULL);  // fixed seed ("materia1")
  DeformationSamples out;
  while (static_cast<int>(out.regular.size()) < regular) {
    const Eigen::Vector3d s(rng.uniform(0.5, 1.6), rng.uniform(0.5, 1.6), rng.uniform(0.5, 1.6));
    const double J = s.prod();
    if (J < 0.2 || J > 3.0) continue;
    out.regular.push_back(rng.rotation() * s.asDiagonal() * rng.rotation());
  }
  while (static_cast<int>(out.near_inverted.size()) < near_inverted) {
    const double s0 = rng.uniform(0.6, 1.5), s1 = rng.uniform(0.6, 1.5), J = rng.uniform(0.005, 0.02);
    const Eigen::Vector3d s(s0, s1, J / (s0 * s1));
    out.near_inverted.push_back(rng.rotation() * s.asDiagonal() * rng.rotation());
  }
  while (static_cast<int>(out.inverted.size()) < inverted) {
    Eigen::Vector3d s(rng.uniform(0.5, 1.6), rng.uniform(0.5, 1.6), rng.uniform(0.5, 1.6));
    const double J = s.prod();
    Eigen::Vector3d sorted = s;
    std::sort(sorted.data(), sorted.data() + 3);
    if (J < 0.2 || J > 3.0 || sorted[1] - sorted[0] < 0.1) continue;
    s[2] = -s[2];  // which stretch is negated does not matter: only det F's sign and |s| are invariants
    out.inverted.push_back(rng.rotation() * s.asDiagonal() * rng.rotation());
  }
  return out;
}

namespace {

void add_lame_checks(Report& report) {
  // Hand-computed: mu = E / (2 (1 + nu)), lambda = E nu / ((1 + nu)(1 - 2 nu)), as fractions.
  struct Case {
    double E, nu, mu, lambda;
    const char* hand;
  };
  const Case cases[] = {
      {1.0, 0.3, 0.38461538461538464, 0.5769230769230769, "mu = 1/2.6 = 5/13, lambda = 0.3/0.52 = 15/26"},
      {210e9, 0.3, 80769230769.23077, 121153846153.84616, "mu = 210e9 * 5/13, lambda = 210e9 * 15/26"},
      {1.0, 0.49, 0.33557046979865773, 16.44295302013423, "mu = 1/2.98 = 50/149, lambda = 0.49/0.0298 = 2450/149"},
      {1.0, 0.0, 0.5, 0.0, "mu = E/2, lambda = 0"},
      {1.0, -0.5, 1.0, -0.5, "mu = 1/(2 * 0.5) = 1, lambda = -0.5/(0.5 * 2) = -1/2"},
      // Errata check for Longva et al. 2020: its published code converted
      // (E, nu) to Lame parameters wrongly; every finite-cell experiment here uses
      // this tested conversion, so Longva et al.'s own materials are checked too:
      // Fig. 5 and the cylinder (E = 3e6, nu = 0.4), the armadillo (5e5, 0.4).
      {3e6, 0.4, 1071428.5714285714, 4285714.2857142857,
       "Longva et al. 2020 Fig. 5: mu = 3e6/2.8 = 7.5e6/7, lambda = 1.2e6/0.28 = 3e7/7"},
      {5e5, 0.4, 178571.42857142857, 714285.71428571429, "Longva et al. 2020 §6.5: mu = 5e5/2.8 = 1.25e6/7, lambda = 5e6/7"},
  };
  // Rounding: <= 4 operations (~2 eps) plus the decimal nu's representation error
  // (eps/2 relative) amplified by d ln lambda / d ln nu = 1/(1+nu) + 2nu/(1-2nu)
  // (<= 50 at nu = 0.49): <= ~30 eps. 64 eps keeps a 2x margin.
  for (const Case& c : cases) {
    const LameParameters p = LameParameters::from_young_poisson(c.E, c.nu);
    const double err = std::max(std::fabs(p.mu - c.mu) / c.mu, std::fabs(p.lambda - c.lambda) / std::max(std::fabs(c.lambda), c.mu));
    report.check("material.lame", fmt::format("E={} nu={}: mu={:.17g} lambda={:.17g}", c.E, c.nu, p.mu, p.lambda), err,
                 64 * kEps, Compare::AtMost,
                 fmt::format("relative error against hand-computed values ({}); 64 eps: a few roundings plus nu's "
                             "representation error times d ln(lambda)/d ln(nu) <= 50",
                             c.hand));
  }
  int accepted = 0;
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  const std::pair<double, double> bad[] = {{0.0, 0.3}, {-1.0, 0.3},  {nan, 0.3},  {inf, 0.3}, {1.0, 0.5},
                                           {1.0, -1.0}, {1.0, 0.7}, {1.0, -1.5}, {1.0, nan}};
  for (auto [E, nu] : bad) {
    try {
      (void)LameParameters::from_young_poisson(E, nu);
      ++accepted;
    } catch (const std::invalid_argument&) {
    }
  }
  report.check("material.lame", "invalid (E, nu) rejected", accepted, 0, Compare::AtMost,
               "count of accepted inputs among E in {0, -1, NaN, inf}, nu in {0.5, -1, 0.7, -1.5, NaN}: all must "
               "throw std::invalid_argument");
}

void add_factory_checks(Report& report) {
  const LameParameters lame = LameParameters::from_young_poisson(1e6, 0.3);
  int wrong = 0;
  for (const std::string& n : material_names()) wrong += make_material(n, lame)->name() == n ? 0 : 1;
  // Valid names found in the message of the exception (0 if none is thrown).
  int listed = 0;
  try {
    (void)make_material("rubber", lame);
  } catch (const std::invalid_argument& e) {
    for (const std::string& n : material_names()) listed += std::string(e.what()).find(n) != std::string::npos;
  }
  report.check("material.factory", "every name constructs its material", wrong, 0, Compare::AtMost,
               "count of names in material_names() whose material reports another name()");
  report.check("material.factory", "unknown name throws, listing valid names", listed,
               static_cast<double>(material_names().size()), Compare::AtLeast,
               "valid names found in the message of the std::invalid_argument make_material(\"rubber\") throws (0 "
               "if it throws none): all of material_names()");
}

// One material and one family of samples: FD rows, for every F where it is defined.
void add_fd_rows(Report& report, const Material& m, const std::string& label, const std::vector<Mat3>& Fs,
                 const std::string& family) {
  double es = 0.0, et = 0.0;
  for (const Mat3& F : Fs) {
    const double h = kFdStep * fd_length_scale(F);
    es = std::max(es, stress_fd_error(m, F, h));
    et = std::max(et, tangent_fd_error(m, F, h));
  }
  const std::string name = fmt::format("{}: {} ({} F)", label, family, Fs.size());
  report.check("material.stress_fd", name, es, kFdTol, Compare::AtMost,
               "max |P - central FD of psi| / max(|P|, mu+|lambda|); step h = 1e-5 l(F), l = smallest singular value "
               "(inverted: also smallest |s_i + s_j|). Predicted truncation (h^2/6)|psi'''| + rounding eps|psi|/h "
               "<~ 1e-8 relative (ratios up to ~1e2 at near-inverted F); 1e-6 leaves ~100x; a missing term gives >~ 1e-2 (material.fd_sensitivity)");
  report.check("material.tangent_fd", name, et, kFdTol, Compare::AtMost,
               "max |dP/dF - central FD of P| / max(|dP/dF|, mu+|lambda|); same step and error model as stress_fd");
}

void add_material_rows(Report& report, const Material& m, const std::string& label, const DeformationSamples& samples,
                       Rng& rng) {
  const double scale = scale_of(m);
  add_fd_rows(report, m, label, samples.regular, "det F in [0.2, 3]");
  add_fd_rows(report, m, label, samples.near_inverted, "near-inverted, det F in [0.005, 0.02]");
  bool inverted_defined = true;
  for (const Mat3& F : samples.inverted) inverted_defined = inverted_defined && m.defined_at(F);
  if (inverted_defined) add_fd_rows(report, m, label, samples.inverted, "inverted, det F in [-3, -0.2]");

  // Symmetry and invariance over every sample where the material is defined.
  std::vector<Mat3> all = samples.regular;
  all.insert(all.end(), samples.near_inverted.begin(), samples.near_inverted.end());
  if (inverted_defined) all.insert(all.end(), samples.inverted.begin(), samples.inverted.end());
  double asym = 0.0, inv = 0.0, inv_min = std::numeric_limits<double>::infinity(), obj = 0.0;
  for (const Mat3& F : all) {
    asym = std::max(asym, tangent_asymmetry(m, F));
    const Mat3 Q = rng.rotation();
    const double psi = m.energy(F);
    const double d = std::fabs(m.energy(Q * F) - psi) / std::max(std::fabs(psi), scale);
    inv = std::max(inv, d);
    inv_min = std::min(inv_min, d);
    const Mat3 P = m.stress(F);
    obj = std::max(obj, max_abs(Mat3(m.stress(Q * F) - Q * P)) / std::max(max_abs(P), scale));
  }
  int mismatches = 0;
  for (const Mat3& F : all) {
    Mat3 P;
    Mat9 H;
    const double psi = m.evaluate(F, &P, &H);
    mismatches += (psi == m.energy(F) && P == m.stress(F) && H == m.stress_derivative(F) &&
                   m.evaluate(F, nullptr, nullptr) == psi)
                      ? 0
                      : 1;
  }
  report.check("material.evaluate", fmt::format("{}: evaluate = energy, stress, stress_derivative ({} F)", label, all.size()),
               mismatches, 0, Compare::AtMost,
               "count of F where the combined evaluate(F, &P, &dPdF) differs in any bit from the separate calls (all "
               "four share one implementation, so a line search comparing energies never sees two roundings)");
  report.check("material.tangent_symmetry", fmt::format("{}: {} F", label, all.size()), asym, kSymTol, Compare::AtMost,
               "max |A - A^T| / max|A|, A = dP/dF: a Hessian, symmetric up to rounding (<~ 20 eps of max|A|); "
               "1e-14 ~ 45 eps");
  if (m.name() == "linear") {
    report.check("material.rotation_invariance", fmt::format("{}: psi(QF) != psi(F), {} F", label, all.size()), inv_min,
                 1e-3, Compare::AtLeast,
                 "documented property, not a defect: small-strain psi depends on sym(F - I), which a rotation changes, "
                 "so min |psi(QF) - psi(F)| / max(|psi|, mu+|lambda|) over random Q is O(1); LinearElastic is valid "
                 "only for small rotations");
  } else {
    report.check("material.rotation_invariance", fmt::format("{}: psi(QF) = psi(F), {} F", label, all.size()), inv,
                 kInvarianceTol, Compare::AtMost,
                 "max |psi(QF) - psi(F)| / max(|psi|, mu+|lambda|), random rotation Q per F: rounding only (<~ 100 eps, "
                 "terms up to ~60 (mu+|lambda|)); 1e-13 ~ 450 eps");
    report.check("material.rotation_invariance", fmt::format("{}: P(QF) = Q P(F), {} F", label, all.size()), obj,
                 kInvarianceTol, Compare::AtMost,
                 "max |P(QF) - Q P(F)| / max(|P|, mu+|lambda|): objectivity of the stress, rounding only; 1e-13 ~ 450 eps");
  }

  // Rest state: zero stress and the linear-elastic tangent.
  const Mat3 I = Mat3::Identity();
  report.check("material.rest", fmt::format("{}: P(I) = 0", label), max_abs(m.stress(I)) / scale, kRestTol,
               Compare::AtMost, "max |P(I)| / (mu+|lambda|): stress-free reference state, to rounding (16 eps)");
  const LinearElastic linear(m.lame());
  report.check("material.rest", fmt::format("{}: dP/dF(I) = linear elasticity", label),
               max_abs(Mat9(m.stress_derivative(I) - linear.tangent())) / scale, kRestTol, Compare::AtMost,
               "max |dP/dF(I) - C| / (mu+|lambda|), C_ijkl = mu (d_ik d_jl + d_il d_jk) + lambda d_ij d_kl: every "
               "model reduces to linear elasticity with the given Lame parameters (Stable Neo-Hookean through its "
               "4/3, 5/6 mapping)");
}

// Domain: Neo-Hookean is undefined for det F <= 0; the others are defined everywhere.
void add_domain_checks(Report& report, const Material& m, const std::string& label, const DeformationSamples& samples) {
  std::vector<Mat3> bad = samples.inverted;
  Mat3 singular = samples.regular[0];
  singular.col(2).setZero();  // det F = 0 exactly (a combination of columns would leave ~1e-17 of either sign)
  bad.push_back(singular);
  bad.push_back(Mat3::Zero());
  bad.push_back(-Mat3::Identity());
  int violations = 0;
  if (m.name() == "neohookean") {
    for (const Mat3& F : bad) {
      const double psi = m.energy(F);
      violations += (std::isinf(psi) && psi > 0) ? 0 : 1;
      violations += m.defined_at(F) ? 1 : 0;
      auto throws_named = [&](auto&& call) {
        try {
          call();
        } catch (const MaterialDomainError& e) {
          const std::string what = e.what();
          return what.find("neohookean") != std::string::npos && what.find("det F") != std::string::npos;
        }
        return false;
      };
      violations += throws_named([&] { (void)m.stress(F); }) ? 0 : 1;
      violations += throws_named([&] { (void)m.stress_derivative(F); }) ? 0 : 1;
      Mat3 P;
      Mat9 H;
      violations += throws_named([&] { (void)m.evaluate(F, &P, &H); }) ? 0 : 1;
      const double only_psi = m.evaluate(F, nullptr, nullptr);
      violations += (std::isinf(only_psi) && only_psi > 0) ? 0 : 1;
    }
    report.check("material.domain", fmt::format("{}: det F <= 0 reported ({} F)", label, bad.size()), violations, 0,
                 Compare::AtMost,
                 "count of violations over inverted, singular (det F = 0), zero and -I: energy must be +inf, "
                 "defined_at false, stress / stress_derivative / evaluate(F, &P, &H) must throw MaterialDomainError "
                 "naming the material and det F, evaluate(F, nullptr, nullptr) must return +inf");
  } else {
    for (const Mat3& F : bad) {
      try {
        Mat3 P;
        Mat9 H;
        const double psi = m.evaluate(F, &P, &H);
        const bool ok = m.defined_at(F) && std::isfinite(psi) && std::isfinite(m.energy(F)) && all_finite(m.stress(F)) &&
                        all_finite(m.stress_derivative(F)) && all_finite(P) && all_finite(H);
        violations += ok ? 0 : 1;
      } catch (const std::exception&) {
        ++violations;
      }
    }
    report.check("material.domain", fmt::format("{}: defined at det F <= 0 ({} F)", label, bad.size()), violations, 0,
                 Compare::AtMost,
                 "count of F among inverted, singular (det F = 0), zero and -I where energy, P or dP/dF is not finite "
                 "or throws (corotated at F = 0 / |s_2| = |s_3| inverted: finite through its floored denominators)");
  }
}

// Negative control: the FD harness must see a plausible bug. Corotated's tangent
// with dR/dF dropped (R treated as constant, a common mistake) and Neo-Hookean's
// with the (mu - lambda log J) G_il G_kj term dropped.
void add_sensitivity_checks(Report& report, const DeformationSamples& samples) {
  const LameParameters lame = LameParameters::from_young_poisson(1e6, 0.3);
  const Corotated corot(lame);
  double worst_corot = std::numeric_limits<double>::infinity();
  for (const Mat3& F : samples.regular) {
    const PolarDecomposition pd = polar_decomposition(F);
    const auto r = Eigen::Map<const Eigen::Matrix<double, 9, 1>>(pd.R.data());
    Mat9 wrong = lame.lambda * r * r.transpose();
    wrong.diagonal().array() += 2.0 * lame.mu;
    worst_corot = std::min(worst_corot, tangent_fd_error(corot, F, kFdStep * fd_length_scale(F), wrong));
  }
  report.check("material.fd_sensitivity", "corotated tangent without dR/dF is rejected", worst_corot, 1e3 * kFdTol,
               Compare::AtLeast,
               "min over the 20 regular F of the tangent FD error of 2 mu I + lambda vec(R) vec(R)^T: must be >= 1000x "
               "the FD tolerance, so the tolerance cannot hide a missing term");
  const Mat3 F = samples.regular[0];
  const Mat3 P = corot.stress(F);
  // A 1e-4 relative error in one entry of P must also be visible to stress_fd.
  struct Perturbed final : Material {
    const Corotated& base;
    Perturbed(const Corotated& b) : Material(b.lame()), base(b) {}
    double evaluate(const Mat3& X, Mat3* P, Mat9* dPdF) const override {
      const double psi = base.evaluate(X, P, dPdF);
      if (P) (*P)(0, 1) += 1e-4 * P->cwiseAbs().maxCoeff();
      return psi;
    }
  } perturbed(corot);
  report.check("material.fd_sensitivity", "P off by 1e-4 of max|P| in one entry is rejected",
               stress_fd_error(perturbed, F, kFdStep * fd_length_scale(F)), kFdTol, Compare::AtLeast,
               fmt::format("stress FD error of corotated P with P(0,1) += 1e-4 max|P| (max|P| = {:.3g}): must exceed the "
                           "1e-6 tolerance",
                           max_abs(P)));
}

// The rotation-variant polar decomposition behind Corotated, on every sample and on
// degenerate F (rotations, a reflection, rank 2, rank 1, zero).
void add_polar_checks(Report& report, const DeformationSamples& samples) {
  std::vector<Mat3> Fs = samples.regular;
  Fs.insert(Fs.end(), samples.near_inverted.begin(), samples.near_inverted.end());
  Fs.insert(Fs.end(), samples.inverted.begin(), samples.inverted.end());
  const Mat3& A = samples.regular[0];
  Mat3 rank2 = A, rank1 = A;
  rank2.col(2) = 0.5 * A.col(0) - 2.0 * A.col(1);
  rank1.col(1) = 3.0 * A.col(0);
  rank1.col(2) = -A.col(0);
  Mat3 reflection = Mat3::Identity();
  reflection(1, 1) = -1.0;
  for (const Mat3& F : {Mat3(Mat3::Identity()), reflection, rank2, rank1, Mat3(Mat3::Zero())}) Fs.push_back(F);
  double orth = 0.0, recon = 0.0, sym = 0.0;
  int sign_wrong = 0;
  for (const Mat3& F : Fs) {
    const PolarDecomposition pd = polar_decomposition(F);
    const double scale = std::max(max_abs(F), std::numeric_limits<double>::min());
    orth = std::max({orth, max_abs(Mat3(pd.R.transpose() * pd.R - Mat3::Identity())), std::fabs(pd.R.determinant() - 1.0)});
    recon = std::max(recon, max_abs(Mat3(pd.R * pd.S - F)) / scale);
    sym = std::max(sym, max_abs(Mat3(pd.S - pd.S.transpose())) / scale);
    const double det = F.determinant();
    if (std::fabs(det) > 1e-12 * scale * scale * scale) sign_wrong += ((det < 0) == (pd.sigma[2] < 0)) ? 0 : 1;
    sign_wrong += (std::fabs(pd.sigma[2]) <= pd.sigma[1] && pd.sigma[1] <= pd.sigma[0]) ? 0 : 1;
  }
  const std::string n = fmt::format("{} F (samples + I, reflection, rank 2, rank 1, zero)", Fs.size());
  const char* why =
      "Jacobi SVD of F (not F^T F): backward stable, errors of O(10) eps of max|F| (3x3 rotations, products of "
      "three factors); 5e-14 ~ 225 eps";
  report.check("material.polar", "R orthogonal, det R = 1: " + n, orth, 5e-14, Compare::AtMost,
               fmt::format("max(|R^T R - I|, |det R - 1|). {}", why));
  report.check("material.polar", "F = R S: " + n, recon, 5e-14, Compare::AtMost,
               fmt::format("max |R S - F| / max|F|. {}", why));
  report.check("material.polar", "S symmetric: " + n, sym, 5e-14, Compare::AtMost,
               fmt::format("max |S - S^T| / max|F|. {}", why));
  report.check("material.polar", "sign of det F on the smallest singular value: " + n, sign_wrong, 0, Compare::AtMost,
               "count of F where sigma_3 < 0 disagrees with det F < 0 (skipped where |det F| <= 1e-12 max|F|^3, "
               "numerically singular) or |sigma_3| <= sigma_2 <= sigma_1 fails");
}

void add_project_psd_checks(Report& report, const DeformationSamples& samples) {
  Rng rng(0x7073645f70726f6aULL);
  std::vector<Mat9> indefinite;
  for (int k = 0; k < 20; ++k) {
    Mat9 A;
    for (int i = 0; i < 81; ++i) A.data()[i] = rng.uniform(-1.0, 1.0);
    indefinite.push_back(0.5 * (A + A.transpose()));
  }
  // Material tangents that lose definiteness: StVK and corotated under compression
  // and inversion, Neo-Hookean near inversion.
  const LameParameters lame = LameParameters::from_young_poisson(1e6, 0.3);
  for (const char* n : {"stvk", "corotated", "stable-neohookean"})
    for (const Mat3& F : samples.inverted) indefinite.push_back(make_material(n, lame)->stress_derivative(F));
  for (const Mat3& F : samples.near_inverted) {
    indefinite.push_back(make_material("stvk", lame)->stress_derivative(F));
    indefinite.push_back(make_material("neohookean", lame)->stress_derivative(F));
  }
  double worst_neg = 0.0, worst_dist = 0.0;
  int negative_inputs = 0;
  for (const Mat9& A : indefinite) {
    const Mat9 sym = 0.5 * (A + A.transpose());
    const Eigen::SelfAdjointEigenSolver<Mat9> in(sym);
    negative_inputs += in.eigenvalues().minCoeff() < 0 ? 1 : 0;
    const Mat9 out = project_psd(A);
    const Eigen::SelfAdjointEigenSolver<Mat9> e(0.5 * (out + out.transpose()));
    worst_neg = std::max(worst_neg, -e.eigenvalues().minCoeff() / e.eigenvalues().cwiseAbs().maxCoeff());
    // The projection is the nearest PSD matrix in the Frobenius norm: the distance
    // is the norm of the negative eigenvalues.
    const double expected = in.eigenvalues().cwiseMin(0.0).norm();
    worst_dist = std::max(worst_dist, std::fabs((sym - out).norm() - expected) / sym.norm());
  }
  report.check("material.project_psd", fmt::format("output PSD ({} matrices, {} indefinite)", indefinite.size(), negative_inputs),
               worst_neg, 1e-12, Compare::AtMost,
               "max over inputs of -min eig / max |eig| of project_psd(A): 20 random symmetric 9x9 with entries in "
               "[-1, 1] and material tangents at inverted / near-inverted F. Eigen-solver rounding is ~9 eps of max "
               "|eig|; 1e-12 is the requested bound");
  report.check("material.project_psd", "distance to the input = norm of its negative eigenvalues", worst_dist, 1e-12,
               Compare::AtMost,
               "| ||A - proj(A)||_F - ||min(eig(A), 0)|| | / ||A||_F: only the negative part is removed (nearest PSD "
               "matrix); rounding ~9 eps");
  // PSD inputs are left unchanged: strictly PD ones bit for bit, singular PSD to rounding.
  double pd_change = 0.0, psd_change = 0.0;
  for (int k = 0; k < 20; ++k) {
    Eigen::Matrix<double, 9, 5> B;
    for (int i = 0; i < 45; ++i) B.data()[i] = rng.uniform(-1.0, 1.0);
    const Mat9 low_rank = B * B.transpose();
    const Mat9 pd = low_rank + 0.1 * Mat9::Identity();
    pd_change = std::max(pd_change, max_abs(Mat9(project_psd(pd) - pd)));
    psd_change = std::max(psd_change, max_abs(Mat9(project_psd(low_rank) - low_rank)) / max_abs(low_rank));
  }
  report.check("material.project_psd", "positive definite input unchanged (20 B B^T + 0.1 I)", pd_change, 0.0,
               Compare::AtMost, "max |proj(A) - A|: a PSD input is returned as is, bit for bit");
  report.check("material.project_psd", "singular PSD input unchanged (20 B B^T, rank 5)", psd_change, 1e-13,
               Compare::AtMost,
               "max |proj(A) - A| / max|A|: the zero eigenvalues come out as +-1e-16, so the matrix may be rebuilt "
               "from its eigen-decomposition V max(D, 0) V^T: rounding ~9 eps of max|A| per entry; 1e-13 ~ 450 eps");
}

}  // namespace

void add_material_checks(Report& report) {
  add_lame_checks(report);
  add_factory_checks(report);
  const DeformationSamples samples = deformation_samples();
  Rng rng(0x726f746174696f6eULL);  // rotations for the invariance checks
  for (double nu : {0.3, 0.49}) {
    const LameParameters lame = LameParameters::from_young_poisson(1e6, nu);
    for (const std::string& n : material_names()) {
      const auto m = make_material(n, lame);
      const std::string label = fmt::format("{} E=1e6 {}", n, fmt_nu(nu));
      add_material_rows(report, *m, label, samples, rng);
      add_domain_checks(report, *m, label, samples);
    }
  }
  add_sensitivity_checks(report, samples);
  add_polar_checks(report, samples);
  add_project_psd_checks(report, samples);
  add_symbolic_material_checks(report);
}

}  // namespace hofem::verification
