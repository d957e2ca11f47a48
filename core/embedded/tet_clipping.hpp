#pragma once
// Convex clipping for embedded quadrature (Longva et al. 2020 §4.5): the part of an
// embedded tetrahedron inside a background cell, as a set of tetrahedra.
//
// A background cell with planar faces is the intersection of half-spaces (6 for
// an axis-aligned or affine hex, 4 for a tet), and the intersection of a tet with
// one half-space is a tet, a prism (split into 3 tets) or nothing. Clipping the
// pieces against each plane in turn therefore yields the intersection already
// split into tetrahedra, so no polyhedron with polygon faces is ever built (Longva et al.
// 2020 clip polyhedra and then tetrahedralises; the result is the same region).
#include <Eigen/Core>

#include <span>
#include <vector>

namespace hofem {

struct Tetrahedron {
  Eigen::Matrix<double, 3, 4> v;  ///< vertices as columns
  double volume() const;          ///< |det[v1-v0, v2-v0, v3-v0]| / 6
};

/// The half-space n . x <= d.
struct HalfSpace {
  Eigen::Vector3d n;
  double d = 0.0;
  double signed_distance(const Eigen::Vector3d& x) const { return n.dot(x) - d; }
};

/// Appends to `out` the pieces of t inside h (0, 1 or 3 tets). Pieces with a
/// volume below `min_volume` (slivers from vertices on the plane) are dropped.
void clip_tetrahedron(const Tetrahedron& t, const HalfSpace& h, std::vector<Tetrahedron>& out, double min_volume);

/// The part of t inside every half-space, as tetrahedra. min_volume as above,
/// relative to t's volume.
std::vector<Tetrahedron> clip_tetrahedron(const Tetrahedron& t, std::span<const HalfSpace> planes,
                                          double relative_min_volume = 1e-14);

/// A convex planar polygon, vertices in order around it.
using ConvexPolygon = std::vector<Eigen::Vector3d>;

/// The part of a convex polygon inside h (one Sutherland-Hodgman pass: a vertex
/// with n . x - d <= on_plane is inside, an edge from below -on_plane to above
/// on_plane is cut). Empty if nothing of it is inside; may be degenerate (zero
/// area) when the polygon only touches the plane - callers drop pieces by area.
/// on_plane > 0 keeps a polygon that lies in the plane whole whichever way its
/// vertices' distances round (in the units of n . x - d).
ConvexPolygon clip_polygon(const ConvexPolygon& polygon, const HalfSpace& h, double on_plane = 0.0);

/// The 6 half-spaces of the box [lo, hi].
std::vector<HalfSpace> box_half_spaces(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi);
/// The 4 half-spaces of a (non-degenerate) tetrahedron.
std::vector<HalfSpace> tetrahedron_half_spaces(const Tetrahedron& t);

}  // namespace hofem
