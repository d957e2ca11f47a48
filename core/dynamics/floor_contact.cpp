#include "dynamics/floor_contact.hpp"

#include <algorithm>

namespace hofem {

namespace {
bool counted(const std::vector<char>* only, Eigen::Index node) { return !only || (*only)[node]; }
}  // namespace

double Floor::energy(const Eigen::VectorXd& x, const std::vector<char>* only) const {
  double e = 0.0;
  for (Eigen::Index i = 0; i < x.size() / 3; ++i) {
    if (!counted(only, i)) continue;
    const double d = depth(x.segment<3>(3 * i));
    if (d > 0.0) e += 0.5 * stiffness * d * d;
  }
  return e;
}

int Floor::add_forces(const Eigen::VectorXd& x, Eigen::VectorXd& f, const std::vector<char>* only) const {
  int contacts = 0;
  for (Eigen::Index i = 0; i < x.size() / 3; ++i) {
    if (!counted(only, i)) continue;
    const double d = depth(x.segment<3>(3 * i));
    if (d > 0.0) {
      f.segment<3>(3 * i) += stiffness * d * normal;
      ++contacts;
    }
  }
  return contacts;
}

void Floor::add_hessian(const Eigen::VectorXd& x, const DofMap& dofs, SparseMatrix& K,
                        const std::vector<char>* only) const {
  const Eigen::Matrix3d H = stiffness * normal * normal.transpose();
  for (Eigen::Index i = 0; i < x.size() / 3; ++i) {
    if (!counted(only, i) || depth(x.segment<3>(3 * i)) <= 0.0) continue;
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) {
        const int ra = dofs.free_index(static_cast<int>(3 * i + a)), rb = dofs.free_index(static_cast<int>(3 * i + b));
        if (ra >= 0 && rb >= 0 && H(a, b) != 0.0) K.coeffRef(ra, rb) += H(a, b);
      }
  }
}

double Floor::max_depth(const Eigen::VectorXd& x) const {
  double m = 0.0;
  for (Eigen::Index i = 0; i < x.size() / 3; ++i) m = std::max(m, depth(x.segment<3>(3 * i)));
  return m;
}

int Floor::contacts(const Eigen::VectorXd& x, const std::vector<char>* only) const {
  int n = 0;
  for (Eigen::Index i = 0; i < x.size() / 3; ++i) n += counted(only, i) && depth(x.segment<3>(3 * i)) > 0.0;
  return n;
}

}  // namespace hofem
