#include "embedded/embedded_quadrature.hpp"

#include "quadrature/rule_library.hpp"

#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace hofem {

std::vector<Tetrahedron> mesh_tetrahedra(const Mesh& mesh) {
  if (mesh.cell != CellType::Tetrahedron)
    throw std::invalid_argument("mesh_tetrahedra: the embedded geometry must be a tetrahedral mesh");
  std::vector<Tetrahedron> tets(mesh.num_elements());
  for (int e = 0; e < mesh.num_elements(); ++e) tets[e].v = mesh.nodes(Eigen::all, mesh.elements.col(e).head<4>());
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

std::vector<Eigen::AlignedBox3d> bounding_boxes(std::span<const Tetrahedron> tets) {
  std::vector<Eigen::AlignedBox3d> boxes;
  boxes.reserve(tets.size());
  for (const Tetrahedron& t : tets) boxes.emplace_back(t.v.rowwise().minCoeff(), t.v.rowwise().maxCoeff());
  return boxes;
}

BoxBucketGrid::BoxBucketGrid(std::vector<Eigen::AlignedBox3d> boxes, int buckets_per_axis) : boxes_(std::move(boxes)) {
  if (boxes_.empty()) {
    lo_.setZero();
    size_.setOnes();
    buckets_.resize(1);
    return;
  }
  n_ = buckets_per_axis > 0 ? buckets_per_axis
                            : std::max(1, static_cast<int>(std::cbrt(static_cast<double>(boxes_.size()))));
  Eigen::AlignedBox3d all;
  for (const Eigen::AlignedBox3d& b : boxes_) all.extend(b);
  lo_ = all.min();
  size_ = (all.max() - all.min()).cwiseMax(1e-300) / n_;
  buckets_.resize(static_cast<size_t>(n_) * n_ * n_);
  for (size_t k = 0; k < boxes_.size(); ++k) {
    if (boxes_[k].isEmpty()) continue;
    const Eigen::Vector3i a = bucket_of(boxes_[k].min()), b = bucket_of(boxes_[k].max());
    for (int i = a.x(); i <= b.x(); ++i)
      for (int j = a.y(); j <= b.y(); ++j)
        for (int l = a.z(); l <= b.z(); ++l) buckets_[index(i, j, l)].push_back(static_cast<int>(k));
  }
}

Eigen::Vector3i BoxBucketGrid::bucket_of(const Eigen::Vector3d& x) const {
  return ((x - lo_).cwiseQuotient(size_)).array().floor().cast<int>().cwiseMax(0).cwiseMin(n_ - 1).matrix();
}

std::vector<int> BoxBucketGrid::candidates(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) const {
  std::vector<int> out;
  if (boxes_.empty()) return out;
  const Eigen::Vector3d a_real = (lo - lo_).cwiseQuotient(size_), b_real = (hi - lo_).cwiseQuotient(size_);
  if ((b_real.array() < 0.0).any() || (a_real.array() >= n_).any()) return out;
  const Eigen::Vector3i a = a_real.array().floor().cast<int>().cwiseMax(0).cwiseMin(n_ - 1);
  const Eigen::Vector3i b = b_real.array().floor().cast<int>().cwiseMax(0).cwiseMin(n_ - 1);
  for (int i = a.x(); i <= b.x(); ++i)
    for (int j = a.y(); j <= b.y(); ++j)
      for (int l = a.z(); l <= b.z(); ++l)
        for (int k : buckets_[index(i, j, l)])
          if ((boxes_[k].min().array() <= hi.array()).all() && (boxes_[k].max().array() >= lo.array()).all())
            out.push_back(k);
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

PhysicalRule box_cell_rule(std::span<const Tetrahedron> tets, const BoxBucketGrid& grid, const Eigen::Vector3d& lo,
                           const Eigen::Vector3d& hi, int degree) {
  const std::vector<HalfSpace> cell = box_half_spaces(lo, hi);
  PhysicalRule rule;
  for (int k : grid.candidates(lo, hi)) add_clipped_rule(tets[k], cell, degree, rule);
  return rule;
}

}  // namespace hofem
