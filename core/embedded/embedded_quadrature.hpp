#pragma once
// Per-cell quadrature for embedded (finite cell) simulation, Longva et al. 2020 §4.5:
// the embedded geometry is a set of tetrahedra; the part of it inside a
// background cell is clipped into tetrahedra (tet_clipping.hpp), and a tet rule
// of degree m is mapped onto each piece. The result integrates polynomials of
// degree <= m over (geometry ∩ cell) exactly; its many points are what the
// simplification of §4.4 then reduces to at most C(m+3, 3).
//
// A uniform bucket grid over the embedded tets' bounding boxes gives each cell
// its candidate tets, so cells do not test every embedded tet (the same grid
// serves the embedded surface's triangles, embedded_surface_quadrature.hpp).
#include "embedded/tet_clipping.hpp"
#include "mesh/mesh.hpp"

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <span>
#include <vector>

namespace hofem {

/// Points (physical coordinates) and weights.
struct PhysicalRule {
  std::vector<Eigen::Vector3d> points;
  std::vector<double> weights;
  int size() const { return static_cast<int>(weights.size()); }
};

/// The vertex tetrahedra of a tetrahedral mesh (its order-1 geometry).
std::vector<Tetrahedron> mesh_tetrahedra(const Mesh& mesh);

/// Appends to `rule` a degree-m rule over the part of `tet` inside every half-space.
void add_clipped_rule(const Tetrahedron& tet, std::span<const HalfSpace> cell, int degree, PhysicalRule& rule);

/// Bounding boxes of tetrahedra (for BoxBucketGrid).
std::vector<Eigen::AlignedBox3d> bounding_boxes(std::span<const Tetrahedron> tets);

/// Uniform grid of buckets over a set of boxes (the bounding boxes of embedded
/// tets or triangles, or of background cells: embedded_points.cpp); each box is
/// listed in every bucket it overlaps, ascending, and an empty box in none.
class BoxBucketGrid {
 public:
  explicit BoxBucketGrid(std::vector<Eigen::AlignedBox3d> boxes, int buckets_per_axis = 0);  ///< 0: ~cbrt(n)
  /// Indices of the boxes that overlap [lo, hi], each once, ascending.
  std::vector<int> candidates(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) const;
  int buckets_per_axis() const { return n_; }
  /// The bucket of a point (clamped to the grid).
  Eigen::Vector3i bucket_of(const Eigen::Vector3d& x) const;
  /// The boxes listed in bucket b.
  const std::vector<int>& bucket(const Eigen::Vector3i& b) const { return buckets_[index(b.x(), b.y(), b.z())]; }
  const Eigen::AlignedBox3d& box(int k) const { return boxes_[k]; }

 private:
  size_t index(int i, int j, int k) const { return (static_cast<size_t>(i) * n_ + j) * n_ + k; }
  Eigen::Vector3d lo_, size_;
  int n_ = 1;
  std::vector<std::vector<int>> buckets_;
  std::vector<Eigen::AlignedBox3d> boxes_;
};

/// Degree-m rule over (embedded tets ∩ box [lo, hi]), using the grid's candidates
/// (a grid over bounding_boxes(tets)).
PhysicalRule box_cell_rule(std::span<const Tetrahedron> tets, const BoxBucketGrid& grid, const Eigen::Vector3d& lo,
                           const Eigen::Vector3d& hi, int degree);

}  // namespace hofem
