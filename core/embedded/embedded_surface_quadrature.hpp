#pragma once
// Quadrature on an embedded surface: Neumann data (tractions) live on the
// embedded boundary, which cuts the background cells just as the embedded volume
// does (Longva et al. 2020 §3; the finite cell literature integrates such data over the
// boundary pieces inside each cut cell).
//
// The load of a traction t is b_i = ∫_Γ N_i t dA, N_i the background basis
// functions. N_i is a polynomial inside each background cell but only C^0 across
// its faces, so one rule over a whole surface triangle integrates kinks wherever
// the triangle crosses a cell face. That error depends on the surface triangles,
// not on the background, so it stops shrinking as the background is refined and
// soon dominates: on the half ball of the Fig. 10 check (background Hex20, 512
// surface triangles), one degree-6 rule per triangle left an L2 error of
// 8.9e-4 at h = 1/16 and 2.3e-3 at h = 1/32, where the clipped rules give
// 6.5e-5 and 8.2e-6 (O(h^3)).
//
// So, as the volume rules are built (§4.5), each triangle is clipped by every
// background cell it crosses (a convex polygon, clip_polygon), the piece is fanned
// into triangles and a triangle rule of the requested degree is mapped onto each.
// On each piece the integrand is a polynomial N_i times the data: the rule is
// exact for data of degree <= degree - (highest total degree of the basis).
//
// A triangle lying in a cell face (a body face on a grid plane) is given to one
// cell only: the one whose outward face normal agrees with the triangle's outward
// normal, i.e. the cell on the body's side, so no area is counted twice. Points
// in inactive cells (dropped slivers, §5.3) are moved to the nearest active cell
// and its basis is extrapolated there, as for embedded points (embedded_points.hpp).
#include "mesh/mesh.hpp"

#include <Eigen/Core>

#include <functional>
#include <vector>

namespace hofem {

struct EmbeddedSurfaceRule {
  std::vector<int> element;  ///< background element of each point
  Eigen::Matrix3Xd xi;       ///< reference coordinates in it
  Eigen::Matrix3Xd points;   ///< physical coordinates
  Eigen::Matrix3Xd normals;  ///< unit outward normal of the surface triangle the point lies on
  Eigen::VectorXd weights;   ///< physical area weights (sum: the surface's area)
  int num_relocated = 0;     ///< points of inactive cells moved to the nearest active one
  int size() const { return static_cast<int>(element.size()); }
};

/// The rule of `degree` on the triangles of `surface` (linear triangles, outward
/// orientation as boundary_surface() gives them), clipped by the cells of an
/// affine `background` (finite_cell_quadrature.hpp: affine_cell). active[e]
/// false: element e takes no points (empty `active` = all active). Throws
/// std::invalid_argument for a surface that is not of linear triangles, a
/// non-finite node, or a non-affine background (naming the element).
EmbeddedSurfaceRule embedded_surface_rule(const Mesh& background, const Mesh& surface, int degree,
                                          const std::vector<char>& active = {});

/// t(X, n): traction at a surface point X with unit outward normal n.
using SurfaceTraction = std::function<Eigen::Vector3d(const Eigen::Vector3d& X, const Eigen::Vector3d& normal)>;

/// b_(3 a + k) = sum_q w_q N_a(xi_q) t_k(X_q, n_q): the consistent load of the
/// traction on the background's nodes, 3 entries per node.
Eigen::VectorXd surface_load_vector(const Mesh& background, const EmbeddedSurfaceRule& rule,
                                    const SurfaceTraction& traction);

}  // namespace hofem
