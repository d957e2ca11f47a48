#include "embedded/embedded_quadrature.hpp"

#include "quadrature/rule_library.hpp"

#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace hofem {

double PhysicalRule::volume() const {
  double v = 0.0;
  for (double w : weights) v += w;
  return v;
}

std::vector<Tetrahedron> mesh_tetrahedra(const Mesh& mesh) {
  if (mesh.cell != CellType::Tetrahedron)
    throw std::invalid_argument("mesh_tetrahedra: the embedded geometry must be a tetrahedral mesh");
  std::vector<Tetrahedron> tets(mesh.num_elements());
  for (int e = 0; e < mesh.num_elements(); ++e)
    for (int i = 0; i < 4; ++i) tets[e].v.col(i) = mesh.nodes.col(mesh.elements(i, e));
  return tets;
}

void add_clipped_rule(const Tetrahedron& tet, std::span<const HalfSpace> cell, int degree, PhysicalRule& rule) {
  const QuadratureRule& ref = quadrature_rule(CellType::Tetrahedron, degree);
  for (const Tetrahedron& piece : clip_tetrahedron(tet, cell)) {
    // x = v0 + J xi on the unit simplex; |det J| = 6 volume.
    Eigen::Matrix3d J;
    J << piece.v.col(1) - piece.v.col(0), piece.v.col(2) - piece.v.col(0), piece.v.col(3) - piece.v.col(0);
    const double det = std::abs(J.determinant());
    for (int q = 0; q < ref.size(); ++q) {
      rule.points.push_back(piece.v.col(0) + J * ref.points.col(q));
      rule.weights.push_back(det * ref.weights[q]);
    }
  }
}

TetBucketGrid::TetBucketGrid(std::span<const Tetrahedron> tets, int buckets_per_axis) {
  if (tets.empty()) {
    lo_.setZero();
    size_.setOnes();
    buckets_.resize(1);
    return;
  }
  n_ = buckets_per_axis > 0 ? buckets_per_axis
                            : std::max(1, static_cast<int>(std::cbrt(static_cast<double>(tets.size()))));
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(1e300), hi = Eigen::Vector3d::Constant(-1e300);
  for (const Tetrahedron& t : tets) {
    tet_lo_.push_back(t.v.rowwise().minCoeff());
    tet_hi_.push_back(t.v.rowwise().maxCoeff());
    lo = lo.cwiseMin(tet_lo_.back());
    hi = hi.cwiseMax(tet_hi_.back());
  }
  lo_ = lo;
  size_ = (hi - lo).cwiseMax(1e-300) / n_;
  buckets_.resize(static_cast<size_t>(n_) * n_ * n_);
  for (size_t k = 0; k < tets.size(); ++k) {
    const Eigen::Vector3i a = ((tet_lo_[k] - lo_).cwiseQuotient(size_)).array().floor().cast<int>().cwiseMax(0).cwiseMin(n_ - 1);
    const Eigen::Vector3i b = ((tet_hi_[k] - lo_).cwiseQuotient(size_)).array().floor().cast<int>().cwiseMax(0).cwiseMin(n_ - 1);
    for (int i = a.x(); i <= b.x(); ++i)
      for (int j = a.y(); j <= b.y(); ++j)
        for (int l = a.z(); l <= b.z(); ++l) buckets_[(static_cast<size_t>(i) * n_ + j) * n_ + l].push_back(static_cast<int>(k));
  }
}

std::vector<int> TetBucketGrid::candidates(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) const {
  std::vector<int> out;
  if (tet_lo_.empty()) return out;
  const Eigen::Vector3d a_real = (lo - lo_).cwiseQuotient(size_), b_real = (hi - lo_).cwiseQuotient(size_);
  if ((b_real.array() < 0.0).any() || (a_real.array() >= n_).any()) return out;
  const Eigen::Vector3i a = a_real.array().floor().cast<int>().cwiseMax(0).cwiseMin(n_ - 1);
  const Eigen::Vector3i b = b_real.array().floor().cast<int>().cwiseMax(0).cwiseMin(n_ - 1);
  for (int i = a.x(); i <= b.x(); ++i)
    for (int j = a.y(); j <= b.y(); ++j)
      for (int l = a.z(); l <= b.z(); ++l)
        for (int k : buckets_[(static_cast<size_t>(i) * n_ + j) * n_ + l])
          if ((tet_lo_[k].array() <= hi.array()).all() && (tet_hi_[k].array() >= lo.array()).all()) out.push_back(k);
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

PhysicalRule box_cell_rule(std::span<const Tetrahedron> tets, const TetBucketGrid& grid, const Eigen::Vector3d& lo,
                           const Eigen::Vector3d& hi, int degree) {
  const std::vector<HalfSpace> cell = box_half_spaces(lo, hi);
  PhysicalRule rule;
  for (int k : grid.candidates(lo, hi)) add_clipped_rule(tets[k], cell, degree, rule);
  return rule;
}

}  // namespace hofem
