#pragma once
// The embedded (finite cell) part of a scene run, Longva et al. 2020 §3.2, §5.3: built
// once before stepping, then asked for the surface displacement each frame.
//   - the finite-cell rules of the background over the embedded tetrahedra
//     (cut cells' stiffness rules simplified unless the scene says not to),
//     stabilised: slivers below drop_fraction dropped, the other cut cells given
//     the full cell's Gauss points at weight `stabilisation`;
//   - the embedded surface (boundary triangles of the tets) with its vertices
//     located in the background cells that integrate something (null rule =
//     uncut = active; a vertex in a dropped cell is extrapolated from the nearest
//     active one);
//   - what it cost and found, for stats.json (stats()).
// The caller passes element_rules() to DynamicsOptions or StaticOptions; the
// background mesh must outlive this object.
#include "embedded/embedded_points.hpp"
#include "embedded/finite_cell_quadrature.hpp"
#include "io/vtu_writer.hpp"
#include "scene/scene.hpp"

#include <nlohmann/json.hpp>

#include <string>
#include <utility>
#include <vector>

namespace hofem {

class SceneEmbedding {
 public:
  /// Throws SceneError (naming the scene file and key) if the geometry cannot be
  /// built, the background is not affine, or the geometry is not inside it.
  SceneEmbedding(const Scene& scene, const Mesh& background);
  SceneEmbedding(const Scene&, Mesh&&) = delete;  // kept by reference: a temporary would dangle

  ElementRules element_rules() const { return cells_.element_rules(); }
  /// Cut cells under a volume fraction of 0.5: the blocks of the "schwarz" preconditioner (Longva et al. 2020 §5.2).
  std::vector<int> preconditioner_blocks() const { return schwarz_block_elements(cells_); }
  /// Per background element: volume of (geometry ∩ cell) / cell volume.
  const std::vector<double>& volume_fraction() const { return cells_.volume_fraction; }
  /// The embedded surface's vertices carried by a background displacement
  /// (3 * background nodes values): their displacements, 3 x surface vertices.
  Eigen::Matrix3Xd surface_displacement(const Eigen::VectorXd& u) const;
  const Mesh& surface() const { return surface_; }
  /// Per background element: it integrates something (uncut, or cut and kept).
  const std::vector<char>& active_cells() const { return active_; }

  /// Writes frame_NNNNN_surface.vtu (point field "displacement") into `dir` and
  /// records it for write_pvd.
  /// `name` is the file name in `dir` (frame_NNNNN_surface.vtu, final_surface.vtu).
  void write_frame(const std::string& dir, const std::string& name, const Eigen::VectorXd& u, double t,
                   VtuFormat format = VtuFormat::ascii);
  /// Writes <name>_surface.pvd listing the frames written.
  void write_pvd(const std::string& dir, const std::string& name) const;
  /// Geometry, cell counts, quadrature points and seconds, stabilisation, extrapolated vertices.
  const nlohmann::json& stats() const { return stats_; }

 private:
  const Mesh& background_;
  CellQuadrature cells_;
  Mesh surface_;
  EmbeddedPointMap surface_map_;
  std::vector<char> active_;
  nlohmann::json stats_;
  std::vector<std::pair<double, std::string>> frames_;
};

/// What measuring a finished finite-cell run needs of its embedding: the
/// geometry's surface and the active background cells, equal to SceneEmbedding's,
/// without the finite-cell rules (no rule is made or tabulated, so a run whose
/// rules took 24 GB can be measured in a fraction of that).
struct EmbeddedGeometry {
  Mesh surface;
  std::vector<char> active;
};
EmbeddedGeometry embedded_geometry(const Scene& scene, const Mesh& background);

}  // namespace hofem
