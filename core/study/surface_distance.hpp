#pragma once
// Scene error of a deformed body against a reference run: the "RMS Hausdorff
// distance" of Longva et al. 2020, "Higher-order finite elements for embedded
// simulation", §6.2 - area-weighted sample points on one deformed boundary
// surface, the distance of each to the other surface, their RMS and maximum.
//
// Surfaces are triangle soups: the caller has already subdivided curved element
// faces into flat triangles, vertices may repeat, and zero-area triangles are
// tolerated (weight zero, no NaN). Each triangle of the sampled surface is sampled
// with the symmetric degree-2 interior rule (barycentric (2/3, 1/6, 1/6) and its
// permutations, weights area/3), so the RMS is a quadrature of the squared
// distance over the surface; the maximum also looks at the triangle vertices.
//
// Distances are exact (the true nearest triangle): a uniform grid of the target
// triangles' bounding boxes is searched in shells of cells around the point until
// the best distance found cannot be beaten by any cell not yet visited; a point
// still undecided after a few shells (far from the surface in cell units, e.g. far
// outside the grid) is finished by branch and bound over a pyramid of the cells'
// occupancy. The point-triangle distance is Ericson's closest point by Voronoi
// regions (Real-Time Collision Detection, §5.1.5).
#include <Eigen/Core>

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace hofem {

/// A surface as flat triangles (a soup: vertices may repeat).
struct TriangleSurface {
  Eigen::Matrix3Xd points;
  std::vector<std::array<int, 3>> triangles;
  /// Sum of the triangles' areas. Throws std::invalid_argument for a vertex index
  /// out of range or a non-finite point.
  double area() const;
};

/// Distances from area-weighted samples on one surface to another.
struct DirectedDistance {
  double rms = 0;   ///< sqrt(sum w d^2 / sum w) over the samples
  double max = 0;   ///< over the samples and the triangle vertices
  double area = 0;  ///< sum of the weights (the sampled surface's area)
  long long samples = 0;
};

struct SurfaceDistance {
  DirectedDistance a_to_b, b_to_a;
  double rms() const;  ///< the larger directed RMS (symmetric, like the Hausdorff distance's max of the two directions)
  double max() const;  ///< the larger directed max (= the Hausdorff distance, to sampling)
};

/// The point of triangle (a, b, c) nearest to p (Ericson, Real-Time Collision
/// Detection, §5.1.5). A degenerate triangle (repeated or collinear vertices) is
/// treated as the union of its three edges.
Eigen::Vector3d closest_point_on_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                          const Eigen::Vector3d& c);

/// Closest-point distance queries against one surface (a uniform grid of its
/// triangles' bounding boxes; exact point-triangle distance). Thread-safe: the
/// query is const. Keeps its own copy of the triangles.
class TriangleDistanceQuery {
 public:
  /// Throws std::invalid_argument for an empty surface (no triangles or zero
  /// area), a vertex index out of range or a non-finite point.
  explicit TriangleDistanceQuery(const TriangleSurface& surface);
  /// To the nearest point of the surface. Throws std::invalid_argument for a
  /// non-finite p.
  double distance(const Eigen::Vector3d& p) const;

 private:
  struct Triangle {
    Eigen::Vector3d a, b, c;
    bool degenerate;
  };
  /// One triangle listed in one cell, with its bounding box: a cheap test read in
  /// cell order before the triangle itself.
  struct Entry {
    Eigen::Vector3d lo, hi;
    std::uint32_t triangle;
  };
  void bin_triangles();
  void build_pyramid();
  void visit_shell(const Eigen::Vector3d& p, const Eigen::Vector3i& home, int r, double& best2) const;
  void search_pyramid(const Eigen::Vector3d& p, double& best2) const;
  Eigen::Vector3i cell_of(const Eigen::Vector3d& x) const;
  double unvisited_squared_distance(const Eigen::Vector3d& p, const Eigen::Vector3i& lo,
                                    const Eigen::Vector3i& hi) const;
  void visit_cell(const Eigen::Vector3d& p, int i, int j, int k, double& best2) const;

  std::vector<Triangle> triangles_;
  std::vector<std::uint32_t> cell_start_;  ///< per cell (x fastest), into entries_; one more at the end
  std::vector<Entry> entries_;             ///< cell by cell
  Eigen::Vector3d lo_, size_, inv_size_;   ///< grid corner, cell edges, cells per unit length (0 on a flat axis)
  Eigen::Vector3i n_;
  std::vector<std::vector<std::uint8_t>>
      occupied_;                          ///< per level: whether a block of 2^level cells a side has triangles
  std::vector<Eigen::Vector3i> level_n_;  ///< blocks along x, y, z per level
};

/// Samples `from` with a fixed area-weighted rule per triangle and measures the distance to `to`.
DirectedDistance directed_distance(const TriangleSurface& from, const TriangleDistanceQuery& to);
/// Both directions.
SurfaceDistance surface_distance(const TriangleSurface& a, const TriangleSurface& b);

}  // namespace hofem
