#include "basis/hex_bases.hpp"

#include "basis/lagrange_nodes.hpp"

namespace hofem {

Hex8Basis::Hex8Basis() { nodes_ = hex_nodes(1); }

std::vector<std::array<int, 3>> Hex8Basis::polynomial_space() const {
  std::vector<std::array<int, 3>> e;
  for (int c = 0; c <= 1; ++c)
    for (int b = 0; b <= 1; ++b)
      for (int a = 0; a <= 1; ++a) e.push_back({a, b, c});
  return e;
}

void Hex8Basis::evaluate(const Eigen::Ref<const Eigen::VectorXd>& x, Eigen::Ref<Eigen::VectorXd> N) const {
  for (int i = 0; i < 8; ++i)
    N[i] = 0.125 * (1 + x[0] * nodes_(0, i)) * (1 + x[1] * nodes_(1, i)) * (1 + x[2] * nodes_(2, i));
}

void Hex8Basis::gradients(const Eigen::Ref<const Eigen::VectorXd>& x, Eigen::Ref<Eigen::MatrixXd> G) const {
  for (int i = 0; i < 8; ++i) {
    const double a = 1 + x[0] * nodes_(0, i), b = 1 + x[1] * nodes_(1, i), c = 1 + x[2] * nodes_(2, i);
    G(i, 0) = 0.125 * nodes_(0, i) * b * c;
    G(i, 1) = 0.125 * a * nodes_(1, i) * c;
    G(i, 2) = 0.125 * a * b * nodes_(2, i);
  }
}

Hex20Basis::Hex20Basis() { nodes_ = hex_nodes(2); }

std::vector<std::array<int, 3>> Hex20Basis::polynomial_space() const {
  std::vector<std::array<int, 3>> e;
  for (int c = 0; c <= 2; ++c)
    for (int b = 0; b <= 2; ++b)
      for (int a = 0; a <= 2; ++a) {
        const int twos = (a == 2) + (b == 2) + (c == 2);
        if (twos <= 1) e.push_back({a, b, c});
      }
  return e;
}

void Hex20Basis::evaluate(const Eigen::Ref<const Eigen::VectorXd>& x, Eigen::Ref<Eigen::VectorXd> N) const {
  for (int i = 0; i < 20; ++i) {
    const Eigen::Vector3d n = nodes_.col(i);
    if (i < 8) {
      N[i] = 0.125 * (1 + x[0] * n[0]) * (1 + x[1] * n[1]) * (1 + x[2] * n[2]) *
             (x[0] * n[0] + x[1] * n[1] + x[2] * n[2] - 2);
    } else {
      double v = 0.25;
      for (int c = 0; c < 3; ++c) v *= n[c] == 0.0 ? (1 - x[c] * x[c]) : (1 + x[c] * n[c]);
      N[i] = v;
    }
  }
}

void Hex20Basis::gradients(const Eigen::Ref<const Eigen::VectorXd>& x, Eigen::Ref<Eigen::MatrixXd> G) const {
  for (int i = 0; i < 20; ++i) {
    const Eigen::Vector3d n = nodes_.col(i);
    if (i < 8) {
      const double f[3] = {1 + x[0] * n[0], 1 + x[1] * n[1], 1 + x[2] * n[2]};
      const double s = x[0] * n[0] + x[1] * n[1] + x[2] * n[2] - 2;
      // d/dx_c [f0 f1 f2 s]/8 = n_c (prod_{e != c} f_e)(s + f_c)/8
      for (int c = 0; c < 3; ++c) {
        const double others = f[(c + 1) % 3] * f[(c + 2) % 3];
        G(i, c) = 0.125 * n[c] * others * (s + f[c]);
      }
    } else {
      double f[3], df[3];
      for (int c = 0; c < 3; ++c) {
        f[c] = n[c] == 0.0 ? 1 - x[c] * x[c] : 1 + x[c] * n[c];
        df[c] = n[c] == 0.0 ? -2 * x[c] : n[c];
      }
      for (int c = 0; c < 3; ++c) G(i, c) = 0.25 * df[c] * f[(c + 1) % 3] * f[(c + 2) % 3];
    }
  }
}

}  // namespace hofem
