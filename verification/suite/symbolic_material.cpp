#include "symbolic_material.hpp"

#include "material_laws.hpp"  // generated: verification/symbolic/derive_material_laws.py

#include <Eigen/Eigenvalues>
#include <Eigen/LU>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <type_traits>

namespace hofem::verification {

namespace {

template <class T>
using Mat3 = Eigen::Matrix<T, 3, 3>;
template <class T>
using Mat9 = Eigen::Matrix<T, 9, 9>;
template <class T>
using RowMajor3 = Eigen::Matrix<T, 3, 3, Eigen::RowMajor>;

// The generated code reads and writes row-major arrays (F[3 i + j] = F_ij).
template <class T>
RowMajor3<T> row_major(const Mat3<T>& A) {
  return RowMajor3<T>(A);
}

// Newton's last step is below this when X is orthogonal to the working
// precision: 1e-17 in long double (eps 1.1e-19), 1e-14 in double (eps 2.2e-16);
// the quadratic convergence leaves X's own error at ~the square of it.
template <class T>
constexpr T polar_tolerance() {
  return std::is_same_v<T, long double> ? T(1e-17L) : T(1e-14);
}

template <class T>
Mat3<T> polar_rotation_in(const Mat3<T>& F) {
  const T det = F.determinant();
  if (!(std::fabs(det) > T(0)) || !F.allFinite())
    throw std::invalid_argument("polar_rotation: F is singular or not finite");
  Mat3<T> X = F;
  for (int it = 0; it < 100; ++it) {
    const Mat3<T> Xinv_t = X.inverse().transpose();
    // Higham's scaling (Frobenius norms) makes the first steps converge from any
    // conditioning; it tends to 1 as X becomes orthogonal.
    const T g = std::sqrt(Xinv_t.norm() / X.norm());
    const Mat3<T> next = T(0.5) * (g * X + Xinv_t / g);
    const T change = (next - X).norm();
    X = next;
    if (change <= polar_tolerance<T>()) break;
  }
  if (det > T(0)) return X;
  // det F < 0: X is a reflection; flip it along the smallest principal stretch.
  const Mat3<T> S = X.transpose() * F;
  const Eigen::SelfAdjointEigenSolver<Mat3<T>> eig(T(0.5) * (S + S.transpose()));
  const Eigen::Matrix<T, 3, 1> v = eig.eigenvectors().col(0);  // ascending eigenvalues
  return X * (Mat3<T>::Identity() - T(2) * v * v.transpose());
}

template <class T>
T energy_stress_in(const std::string& name, T mu, T lambda, const Mat3<T>& F, Mat3<T>* P) {
  const RowMajor3<T> f = row_major(F);
  T psi = T(0);
  RowMajor3<T> p;
  if (name == "linear") symbolic::linear_energy_stress(f.data(), mu, lambda, &psi, p.data());
  else if (name == "stvk") symbolic::stvk_energy_stress(f.data(), mu, lambda, &psi, p.data());
  else if (name == "neohookean") symbolic::neohookean_energy_stress(f.data(), mu, lambda, &psi, p.data());
  else if (name == "stable-neohookean")
    symbolic::stable_neohookean_energy_stress(f.data(), mu, lambda, &psi, p.data());
  else {
    const RowMajor3<T> r = row_major(polar_rotation_in<T>(F));
    symbolic::corotated_energy_stress(f.data(), r.data(), mu, lambda, &psi, p.data());
  }
  if (P) *P = p;
  return psi;
}

template <class T>
Mat9<T> tangent_in(const std::string& name, T mu, T lambda, const Mat3<T>& F) {
  const RowMajor3<T> f = row_major(F);
  Eigen::Matrix<T, 81, 1> a;  // a[9 (3 i + j) + 3 k + l] = dP_ij / dF_kl
  Mat9<T> A;
  if (name == "corotated") {
    // The five-point central difference (error h^4 |d^5 P| / 30): R(F)'s
    // derivatives grow like 1 / (s_j + s_k)^n, and inverted F brings that sum
    // down to ~0.1 (two stretches of opposite sign), where the three-point
    // difference's h^2 term reached 1e-10. At h = 1e-4 the truncation is ~1e-11
    // at s_j + s_k = 0.1 and the round-off ~eps / h (1e-15 in long double,
    // 2e-12 in double).
    const T h = T(1e-4L) * std::max(T(1), F.norm());
    auto P_at = [&](int k, int l, T step) {
      Mat3<T> Fs = F, P;
      Fs(k, l) += step;
      energy_stress_in<T>(name, mu, lambda, Fs, &P);
      return P;
    };
    for (int k = 0; k < 3; ++k)
      for (int l = 0; l < 3; ++l) {
        const Mat3<T> dP =
            (T(8) * (P_at(k, l, h) - P_at(k, l, -h)) - (P_at(k, l, 2 * h) - P_at(k, l, -2 * h))) / (T(12) * h);
        for (int i = 0; i < 3; ++i)
          for (int j = 0; j < 3; ++j) A(i + 3 * j, k + 3 * l) = dP(i, j);
      }
    return A;
  }
  if (name == "linear") symbolic::linear_tangent(f.data(), mu, lambda, a.data());
  else if (name == "stvk") symbolic::stvk_tangent(f.data(), mu, lambda, a.data());
  else if (name == "neohookean") symbolic::neohookean_tangent(f.data(), mu, lambda, a.data());
  else symbolic::stable_neohookean_tangent(f.data(), mu, lambda, a.data());
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k)
        for (int l = 0; l < 3; ++l) A(i + 3 * j, k + 3 * l) = a[9 * (3 * i + j) + 3 * k + l];
  return A;
}

}  // namespace

std::vector<std::string> symbolic_material_names() {
  return {"linear", "stvk", "corotated", "neohookean", "stable-neohookean"};
}

Eigen::Matrix<long double, 3, 3> polar_rotation(const Eigen::Matrix<long double, 3, 3>& F) {
  return polar_rotation_in<long double>(F);
}

SymbolicMaterial::SymbolicMaterial(std::string name, double mu, double lambda)
    : name_(std::move(name)), mu_(mu), lambda_(lambda) {
  const auto names = symbolic_material_names();
  if (std::find(names.begin(), names.end(), name_) == names.end())
    throw std::invalid_argument(fmt::format("SymbolicMaterial: no law for '{}'", name_));
}

double SymbolicMaterial::energy(const Eigen::Matrix3d& F) const {
  return static_cast<double>(energy_stress_in<long double>(name_, mu_, lambda_, F.cast<long double>(), nullptr));
}

Eigen::Matrix3d SymbolicMaterial::stress(const Eigen::Matrix3d& F) const {
  Mat3<long double> P;
  energy_stress_in<long double>(name_, mu_, lambda_, F.cast<long double>(), &P);
  return P.cast<double>();
}

Eigen::Matrix<double, 9, 9> SymbolicMaterial::tangent(const Eigen::Matrix3d& F) const {
  return tangent_in<long double>(name_, mu_, lambda_, F.cast<long double>()).cast<double>();
}

// In double, unlike the pointwise laws above: the body force's relative error
// (~1e-15; ~1e-12 for the corotated law's difference quotient) is four orders
// or more below the finest MMS run's relative L2 error, and long double's
// sinl/cosl and x87 arithmetic made this the MMS family's largest cost (a third
// of its profile, evaluated at every load quadrature point).
Eigen::Vector3d SymbolicMaterial::mms_body_force(const Eigen::Vector3d& X, double s) const {
  double u[3], G[9], H[27];  // G[3 i + j] = du_i/dX_j, H[9 k + 3 l + j] = d2u_k/dX_l dX_j
  symbolic::manufactured_displacement(X.data(), s, u, G, H);
  Eigen::Matrix3d F = Eigen::Matrix3d::Identity();
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) F(i, j) += G[3 * i + j];
  const Mat9<double> A = tangent_in<double>(name_, static_cast<double>(mu_), static_cast<double>(lambda_), F);
  Eigen::Vector3d f;
  for (int i = 0; i < 3; ++i) {
    double sum = 0.0;
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k)
        for (int l = 0; l < 3; ++l) sum += A(i + 3 * j, k + 3 * l) * H[9 * k + 3 * l + j];
    f[i] = -sum;
  }
  return f;
}

}  // namespace hofem::verification
