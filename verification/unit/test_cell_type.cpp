// The corner-face tables of the reference cells (quadrature/cell_type.hpp),
// checked against the reference vertices rather than against a second copy.
#include "quadrature/cell_type.hpp"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <limits>
#include <vector>

namespace hofem {
namespace {

// Every face lies on the cell's boundary (interior margin exactly 0 at its
// vertices, whose coordinates are 0 and +-1; at its centroid within a few ulps,
// as a triangle's centroid holds rounded thirds), is planar, and has its right-hand normal pointing
// away from the cell centroid; each vertex lies on exactly three faces.
template <std::size_t N, std::size_t M>
void expect_outward_boundary_faces(CellType cell, const std::array<std::array<int, M>, N>& faces) {
  const int per_face = static_cast<int>(M);
  const Eigen::MatrixXd v = reference_vertices(cell);
  const Eigen::Vector3d centre = v.rowwise().mean();
  std::vector<int> faces_at(v.cols(), 0);
  for (std::size_t i = 0; i < N; ++i) {
    const std::array<int, M>& f = faces[i];
    Eigen::Vector3d mid = Eigen::Vector3d::Zero();
    for (int k : f) {
      EXPECT_EQ(interior_margin(cell, v.col(k)), 0.0) << name(cell) << " face at " << i;
      mid += v.col(k) / per_face;
      ++faces_at[k];
    }
    EXPECT_NEAR(interior_margin(cell, mid), 0.0, 4 * std::numeric_limits<double>::epsilon()) << name(cell) << " face " << i << " is not on the boundary";
    const Eigen::Vector3d a = v.col(f[0]), b = v.col(f[1]), c = v.col(f[per_face - 1]);
    const Eigen::Vector3d normal = (b - a).cross(c - a);
    EXPECT_GT(normal.dot(mid - centre), 0.0) << name(cell) << " face " << i << " points inwards";
    for (int k : f) EXPECT_EQ(normal.dot(v.col(k) - a), 0.0) << name(cell) << " face " << i;
  }
  for (std::size_t k = 0; k < faces_at.size(); ++k) EXPECT_EQ(faces_at[k], 3) << name(cell) << " vertex " << k;
}

TEST(CellType, CornerFacesAreOutwardBoundaryFaces) {
  expect_outward_boundary_faces(CellType::Tetrahedron, kTetrahedronFaces);
  expect_outward_boundary_faces(CellType::Hexahedron, kHexahedronFaces);
  // Face i of the tetrahedron is the one opposite vertex i.
  for (int i = 0; i < 4; ++i)
    for (int k : kTetrahedronFaces[i]) EXPECT_NE(k, i);
}

}  // namespace
}  // namespace hofem
