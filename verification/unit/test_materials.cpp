// Materials: error paths, closed forms at simple F, and the material suite as a whole.
#include "material/corotated.hpp"
#include "material/material.hpp"
#include "material/neo_hookean.hpp"
#include "material/stable_neo_hookean.hpp"
#include "material_checks.hpp"

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace hofem {
namespace {

const LameParameters kLame = LameParameters::from_young_poisson(1e6, 0.3);

Mat3 diag(double a, double b, double c) { return Eigen::Vector3d(a, b, c).asDiagonal(); }

TEST(MaterialLame, HandComputedValues) {
  const LameParameters p = LameParameters::from_young_poisson(1.0, 0.3);
  EXPECT_NEAR(p.mu, 5.0 / 13.0, 1e-15);       // 1 / 2.6
  EXPECT_NEAR(p.lambda, 15.0 / 26.0, 1e-15);  // 0.3 / 0.52
  const LameParameters q = LameParameters::from_young_poisson(2.0, 0.0);
  EXPECT_EQ(q.mu, 1.0);
  EXPECT_EQ(q.lambda, 0.0);
}

TEST(MaterialLame, RejectsInvalidInput) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(LameParameters::from_young_poisson(0.0, 0.3), std::invalid_argument);
  EXPECT_THROW(LameParameters::from_young_poisson(-5.0, 0.3), std::invalid_argument);
  EXPECT_THROW(LameParameters::from_young_poisson(nan, 0.3), std::invalid_argument);
  EXPECT_THROW(LameParameters::from_young_poisson(1.0, 0.5), std::invalid_argument);
  EXPECT_THROW(LameParameters::from_young_poisson(1.0, -1.0), std::invalid_argument);
  EXPECT_THROW(LameParameters::from_young_poisson(1.0, nan), std::invalid_argument);
  EXPECT_NO_THROW(LameParameters::from_young_poisson(1.0, 0.4999));
  EXPECT_NO_THROW(LameParameters::from_young_poisson(1.0, -0.9999));
}

TEST(MaterialFactory, NamesAndUnknownName) {
  ASSERT_EQ(material_names().size(), 5u);
  for (const std::string& n : material_names()) EXPECT_EQ(make_material(n, kLame)->name(), n);
  try {
    (void)make_material("mooney-rivlin", kLame);
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("mooney-rivlin"), std::string::npos);
    for (const std::string& n : material_names()) EXPECT_NE(what.find(n), std::string::npos) << what;
  }
  EXPECT_TRUE(make_material("corotated", kLame)->needs_polar_decomposition());
  for (const char* n : {"linear", "stvk", "neohookean", "stable-neohookean"})
    EXPECT_FALSE(make_material(n, kLame)->needs_polar_decomposition()) << n;
}

TEST(MaterialNeoHookean, UndefinedForNonPositiveDeterminant) {
  const NeoHookean nh(kLame);
  for (const Mat3& F : {diag(1.0, 1.0, -0.5), diag(1.0, 1.0, 0.0), Mat3(Mat3::Zero())}) {
    EXPECT_FALSE(nh.defined_at(F));
    EXPECT_EQ(nh.energy(F), std::numeric_limits<double>::infinity());
    EXPECT_THROW((void)nh.stress(F), MaterialDomainError);
    EXPECT_THROW((void)nh.stress_derivative(F), MaterialDomainError);
    Mat3 P;
    EXPECT_THROW((void)nh.evaluate(F, &P, nullptr), MaterialDomainError);
    EXPECT_EQ(nh.evaluate(F, nullptr, nullptr), std::numeric_limits<double>::infinity());
  }
  try {
    (void)nh.stress(diag(1.0, 2.0, -0.25));
    FAIL() << "expected MaterialDomainError";
  } catch (const MaterialDomainError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("neohookean"), std::string::npos) << what;
    EXPECT_NE(what.find("det F = -0.5"), std::string::npos) << what;
  }
}

TEST(MaterialNeoHookean, UniaxialClosedForm) {
  // F = diag(s, 1, 1): P_00 = mu (s - 1/s) + lambda log(s) / s, P_11 = lambda log(s).
  const NeoHookean nh(kLame);
  const double s = 1.3;
  const Mat3 P = nh.stress(diag(s, 1, 1));
  EXPECT_NEAR(P(0, 0), kLame.mu * (s - 1 / s) + kLame.lambda * std::log(s) / s, 1e-9 * kLame.mu);
  EXPECT_NEAR(P(1, 1), kLame.lambda * std::log(s), 1e-9 * kLame.mu);
  EXPECT_NEAR(P(0, 1), 0.0, 1e-9 * kLame.mu);
}

TEST(MaterialStableNeoHookean, FiniteEverywhereAndRestStable) {
  const StableNeoHookean snh(kLame);
  EXPECT_DOUBLE_EQ(snh.model_mu(), 4.0 / 3.0 * kLame.mu);
  EXPECT_DOUBLE_EQ(snh.model_lambda(), kLame.lambda + 5.0 / 6.0 * kLame.mu);
  EXPECT_DOUBLE_EQ(snh.alpha(), 1.0 + 0.75 * snh.model_mu() / snh.model_lambda());
  EXPECT_LT(snh.stress(Mat3::Identity()).cwiseAbs().maxCoeff(), 1e-15 * (kLame.mu + kLame.lambda));
  for (const Mat3& F : {diag(1.0, 1.0, -0.5), diag(1.0, 1.0, 0.0), Mat3(Mat3::Zero()), Mat3(-Mat3::Identity())}) {
    EXPECT_TRUE(snh.defined_at(F));
    EXPECT_TRUE(std::isfinite(snh.energy(F)));
    EXPECT_NO_THROW({
      EXPECT_TRUE(snh.stress(F).allFinite());
      EXPECT_TRUE(snh.stress_derivative(F).allFinite());
    });
  }
  // Inverting pushes back: at F = diag(1, 1, -0.5) the stress opposes further compression of the third axis.
  EXPECT_LT(snh.stress(diag(1.0, 1.0, -0.5))(2, 2), 0.0);
  EXPECT_THROW(StableNeoHookean(LameParameters{}), std::invalid_argument);
}

TEST(MaterialCorotated, PolarDecompositionOfReflection) {
  // det F < 0: R must still be a rotation and F = R S with S symmetric.
  const Mat3 F = diag(2.0, 1.5, -0.5);
  const PolarDecomposition pd = polar_decomposition(F);
  EXPECT_NEAR(pd.R.determinant(), 1.0, 1e-14);
  EXPECT_LT((pd.R.transpose() * pd.R - Mat3::Identity()).cwiseAbs().maxCoeff(), 1e-14);
  EXPECT_LT((pd.R * pd.S - F).cwiseAbs().maxCoeff(), 1e-14);
  EXPECT_LT((pd.S - pd.S.transpose()).cwiseAbs().maxCoeff(), 1e-14);
  // The smallest stretch carries the sign: R = I, S = F.
  EXPECT_LT((pd.R - Mat3::Identity()).cwiseAbs().maxCoeff(), 1e-14);
  EXPECT_NEAR(pd.sigma[2], -0.5, 1e-14);
}

TEST(MaterialCorotated, RotationIsStressFree) {
  const Corotated c(kLame);
  const Mat3 Q = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  EXPECT_LT(std::fabs(c.energy(Q)), 1e-20 * kLame.mu);
  EXPECT_LT(c.stress(Q).cwiseAbs().maxCoeff(), 1e-9 * kLame.mu);
}

TEST(MaterialDerivatives, MatchFiniteDifferences) {
  const auto samples = verification::deformation_samples(5, 2, 3);
  for (const std::string& n : material_names()) {
    const auto m = make_material(n, kLame);
    std::vector<Mat3> Fs = samples.regular;
    Fs.insert(Fs.end(), samples.near_inverted.begin(), samples.near_inverted.end());
    if (n != "neohookean") Fs.insert(Fs.end(), samples.inverted.begin(), samples.inverted.end());
    for (const Mat3& F : Fs) {
      const double h = 1e-5 * verification::fd_length_scale(F);
      EXPECT_LT(verification::stress_fd_error(*m, F, h), 1e-6) << n;
      EXPECT_LT(verification::tangent_fd_error(*m, F, h), 1e-6) << n;
      EXPECT_LT(verification::tangent_asymmetry(*m, F), 1e-14) << n;
      // The combined call agrees with the separate ones bit for bit.
      Mat3 P;
      Mat9 H;
      EXPECT_EQ(m->evaluate(F, &P, &H), m->energy(F)) << n;
      EXPECT_EQ(P, m->stress(F)) << n;
      EXPECT_EQ(H, m->stress_derivative(F)) << n;
      EXPECT_EQ(m->evaluate(F, nullptr, nullptr), m->energy(F)) << n;
    }
  }
}

TEST(MaterialProjectPsd, ClampsNegativeEigenvaluesAndKeepsPsd) {
  Mat9 D = Mat9::Zero();
  for (int i = 0; i < 9; ++i) D(i, i) = i - 4.0;  // -4 .. 4
  const Mat9 P = project_psd(D);
  for (int i = 0; i < 9; ++i) EXPECT_NEAR(P(i, i), std::max(i - 4.0, 0.0), 1e-14);
  const Mat9 spd = D.cwiseAbs() + Mat9::Identity();
  EXPECT_EQ(project_psd(spd), spd);
}

TEST(MaterialSuite, AllChecksPass) {
  verification::Report report;
  verification::add_material_checks(report);
  EXPECT_GT(report.rows().size(), 50u);
  for (const auto& r : report.rows())
    EXPECT_TRUE(r.pass) << r.group << " / " << r.name << ": measured " << r.measured << " threshold " << r.threshold;
}

}  // namespace
}  // namespace hofem
