#include "symbolic_material.hpp"

#include "material_laws.hpp"  // generated: verification/symbolic/derive_material_laws.py

#include <Eigen/Eigenvalues>
#include <Eigen/LU>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace hofem::verification {

namespace {

using Mat3L = Eigen::Matrix<long double, 3, 3>;
using Mat9L = Eigen::Matrix<long double, 9, 9>;
using RowMajor3L = Eigen::Matrix<long double, 3, 3, Eigen::RowMajor>;

// The generated code reads and writes row-major arrays (F[3 i + j] = F_ij).
RowMajor3L row_major(const Mat3L& A) { return RowMajor3L(A); }

}  // namespace

std::vector<std::string> symbolic_material_names() {
  return {"linear", "stvk", "corotated", "neohookean", "stable-neohookean"};
}

Mat3L polar_rotation(const Mat3L& F) {
  const long double det = F.determinant();
  if (!(std::fabs(det) > 0.0L) || !F.allFinite())
    throw std::invalid_argument("polar_rotation: F is singular or not finite");
  Mat3L X = F;
  for (int it = 0; it < 100; ++it) {
    const Mat3L Xinv_t = X.inverse().transpose();
    // Higham's scaling (Frobenius norms) makes the first steps converge from any
    // conditioning; it tends to 1 as X becomes orthogonal.
    const long double g = std::sqrt(Xinv_t.norm() / X.norm());
    const Mat3L next = 0.5L * (g * X + Xinv_t / g);
    const long double change = (next - X).norm();
    X = next;
    if (change <= 1e-17L) break;
  }
  if (det > 0.0L) return X;
  // det F < 0: X is a reflection; flip it along the smallest principal stretch.
  const Mat3L S = X.transpose() * F;
  const Eigen::SelfAdjointEigenSolver<Mat3L> eig(0.5L * (S + S.transpose()));
  const Eigen::Matrix<long double, 3, 1> v = eig.eigenvectors().col(0);  // ascending eigenvalues
  return X * (Mat3L::Identity() - 2.0L * v * v.transpose());
}

SymbolicMaterial::SymbolicMaterial(std::string name, double mu, double lambda)
    : name_(std::move(name)), mu_(mu), lambda_(lambda) {
  const auto names = symbolic_material_names();
  if (std::find(names.begin(), names.end(), name_) == names.end())
    throw std::invalid_argument(fmt::format("SymbolicMaterial: no law for '{}'", name_));
}

long double SymbolicMaterial::energy_stress(const Mat3L& F, Mat3L* P) const {
  const RowMajor3L f = row_major(F);
  long double psi = 0.0L;
  RowMajor3L p;
  if (name_ == "linear") symbolic::linear_energy_stress(f.data(), mu_, lambda_, &psi, p.data());
  else if (name_ == "stvk") symbolic::stvk_energy_stress(f.data(), mu_, lambda_, &psi, p.data());
  else if (name_ == "neohookean") symbolic::neohookean_energy_stress(f.data(), mu_, lambda_, &psi, p.data());
  else if (name_ == "stable-neohookean")
    symbolic::stable_neohookean_energy_stress(f.data(), mu_, lambda_, &psi, p.data());
  else {
    const RowMajor3L r = row_major(polar_rotation(F));
    symbolic::corotated_energy_stress(f.data(), r.data(), mu_, lambda_, &psi, p.data());
  }
  if (P) *P = p;
  return psi;
}

Mat9L SymbolicMaterial::tangent_l(const Mat3L& F) const {
  const RowMajor3L f = row_major(F);
  Eigen::Matrix<long double, 81, 1> a;  // a[9 (3 i + j) + 3 k + l] = dP_ij / dF_kl
  Mat9L A;
  if (name_ == "corotated") {
    // The five-point central difference (error h^4 |d^5 P| / 30): R(F)'s
    // derivatives grow like 1 / (s_j + s_k)^n, and inverted F brings that sum
    // down to ~0.1 (two stretches of opposite sign), where the three-point
    // difference's h^2 term reached 1e-10. At h = 1e-4 the truncation is ~1e-11
    // at s_j + s_k = 0.1 and the round-off ~eps_ld / h = 1e-15.
    const long double h = 1e-4L * std::max(1.0L, F.norm());
    auto P_at = [&](int k, int l, long double step) {
      Mat3L Fs = F, P;
      Fs(k, l) += step;
      energy_stress(Fs, &P);
      return P;
    };
    for (int k = 0; k < 3; ++k)
      for (int l = 0; l < 3; ++l) {
        const Mat3L dP =
            (8.0L * (P_at(k, l, h) - P_at(k, l, -h)) - (P_at(k, l, 2 * h) - P_at(k, l, -2 * h))) / (12.0L * h);
        for (int i = 0; i < 3; ++i)
          for (int j = 0; j < 3; ++j) A(i + 3 * j, k + 3 * l) = dP(i, j);
      }
    return A;
  }
  if (name_ == "linear") symbolic::linear_tangent(f.data(), mu_, lambda_, a.data());
  else if (name_ == "stvk") symbolic::stvk_tangent(f.data(), mu_, lambda_, a.data());
  else if (name_ == "neohookean") symbolic::neohookean_tangent(f.data(), mu_, lambda_, a.data());
  else symbolic::stable_neohookean_tangent(f.data(), mu_, lambda_, a.data());
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k)
        for (int l = 0; l < 3; ++l) A(i + 3 * j, k + 3 * l) = a[9 * (3 * i + j) + 3 * k + l];
  return A;
}

double SymbolicMaterial::energy(const Eigen::Matrix3d& F) const {
  return static_cast<double>(energy_stress(F.cast<long double>(), nullptr));
}

Eigen::Matrix3d SymbolicMaterial::stress(const Eigen::Matrix3d& F) const {
  Mat3L P;
  energy_stress(F.cast<long double>(), &P);
  return P.cast<double>();
}

Eigen::Matrix<double, 9, 9> SymbolicMaterial::tangent(const Eigen::Matrix3d& F) const {
  return tangent_l(F.cast<long double>()).cast<double>();
}

Eigen::Vector3d SymbolicMaterial::mms_body_force(const Eigen::Vector3d& X, double s) const {
  const Eigen::Matrix<long double, 3, 1> x = X.cast<long double>();
  long double u[3], G[9], H[27];  // G[3 i + j] = du_i/dX_j, H[9 k + 3 l + j] = d2u_k/dX_l dX_j
  symbolic::manufactured_displacement(x.data(), static_cast<long double>(s), u, G, H);
  Mat3L F = Mat3L::Identity();
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) F(i, j) += G[3 * i + j];
  const Mat9L A = tangent_l(F);
  Eigen::Vector3d f;
  for (int i = 0; i < 3; ++i) {
    long double sum = 0.0L;
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k)
        for (int l = 0; l < 3; ++l) sum += A(i + 3 * j, k + 3 * l) * H[9 * k + 3 * l + j];
    f[i] = static_cast<double>(-sum);
  }
  return f;
}

}  // namespace hofem::verification
