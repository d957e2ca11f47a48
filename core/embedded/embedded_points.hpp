#pragma once
// Embedded geometry carried by the background solution (Longva et al. 2020 §3, §5.3):
// each embedded vertex sits in a background cell at reference coordinates xi and
// moves with u(X) = sum_i N_i(xi) u_i. A vertex whose cell was dropped (volume
// fraction below the threshold) or is otherwise inactive is extrapolated from
// the nearest active cell: the same formula with xi outside the reference cell.
//
// Also the embedded surface (boundary triangles of the embedded tet mesh), for
// output beside the background mesh.
#include "mesh/mesh.hpp"

#include <Eigen/Core>

#include <vector>

namespace hofem {

struct EmbeddedPointMap {
  std::vector<int> element;       ///< background element of each point
  Eigen::Matrix3Xd xi;            ///< reference coordinates in it
  std::vector<char> extrapolated; ///< the point lies outside its element
  int num_extrapolated = 0;
  int size() const { return static_cast<int>(element.size()); }
};

/// Locates `points` (physical, 3 x n) in the cells of `background`: affine
/// cells by their exact inverse map, curved ones (isoparametric Tet10+, tube
/// Hex8/Hex20) by Newton's method on the map. active[e] false keeps points out
/// of element e (empty, dropped); empty `active` = all active. A point inside no
/// active cell goes to the nearest active cell around it (extrapolated).
/// Throws std::invalid_argument if no cell is active, a cell is degenerate or a
/// point is not finite.
EmbeddedPointMap locate_embedded_points(const Mesh& background, const Eigen::Matrix3Xd& points,
                                        const std::vector<char>& active = {});

/// u at the located points (3 x n) from a background field of 3 * num_nodes values.
Eigen::Matrix3Xd interpolate_at_points(const Mesh& background, const EmbeddedPointMap& map, const Eigen::VectorXd& u);

struct PointValues {
  Eigen::Matrix3Xd value;                  ///< u at each point
  std::vector<Eigen::Matrix3d> gradient;   ///< du_a/dX_b at each point (when asked for)
};
/// u, and optionally its gradient with respect to the reference coordinates X,
/// at the located points.
PointValues evaluate_at_points(const Mesh& mesh, const EmbeddedPointMap& map, const Eigen::VectorXd& u,
                               bool with_gradient);

/// The boundary of a tetrahedral mesh (faces of one tet only) as linear
/// triangles, outward (right-handed) orientation, on the boundary's vertices
/// only; `vertex_of` (optional) receives each surface node's node id in `tets`.
Mesh boundary_surface(const Mesh& tets, std::vector<int>* vertex_of = nullptr);

}  // namespace hofem
