#include "scene/scene_embedding.hpp"
#include "scene/scene_mesh.hpp"

#include "assembly/assembler.hpp"
#include "embedded/embedded_quadrature.hpp"
#include "io/vtu_writer.hpp"

#include <Eigen/LU>
#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <stdexcept>

namespace hofem {

namespace {

using Clock = std::chrono::steady_clock;

// Volume of an affine background cell: |det A| times the reference cell's volume.
double cell_volume(const Mesh& background, int e) {
  return std::abs(affine_cell(background, e).A.determinant()) * reference_cell_volume(background.cell);
}

}  // namespace

SceneEmbedding::SceneEmbedding(const Scene& s, const Mesh& background) : background_(background) {
  const auto t0 = Clock::now();
  const SceneEmbedded& options = s.embedded.value();
  const Mesh geometry = build_embedded_mesh(s);
  const std::vector<Tetrahedron> tets = mesh_tetrahedra(geometry);
  double geometry_volume = 0.0;
  for (const Tetrahedron& t : tets) geometry_volume += t.volume();

  FiniteCellOptions fc;
  fc.simplify = options.simplify;
  fc.stiffness_degree = options.stiffness_degree;
  // Moment-fitted mass rules (finite_cell_quadrature.hpp): the same mass matrix
  // to rounding, ~165 instead of ~3,900 tabulated points per cut Hex20 cell.
  fc.fit_mass = true;
  try {
    cells_ = finite_cell_quadrature(background, tets, fc);
  } catch (const std::invalid_argument& e) {
    // Curved or non-parallelepiped background cells (a .msh background).
    throw SceneError(
        fmt::format("{}: mesh: {} (the background of an embedded scene needs affine cells)", s.file, e.what()));
  }
  const int ne = background.num_elements();
  int uncut = 0, cut = 0, empty = 0;
  double captured = 0.0;
  for (int e = 0; e < ne; ++e) {
    if (!cells_.rules[e]) ++uncut;
    else if (cells_.points_before[e] > 0) ++cut;
    else ++empty;
    if (cells_.volume_fraction[e] > 0.0) captured += cells_.volume_fraction[e] * cell_volume(background, e);
  }
  // Material outside the background would silently vanish from the model. The
  // clipped rules integrate constants exactly, so only round-off separates the
  // two volumes when the geometry is inside (relative 1e-12 or so; 1e-8 leaves room).
  if (captured < (1.0 - 1e-8) * geometry_volume)
    throw SceneError(fmt::format("{}: embedded: {:.3g} % of the geometry's volume lies outside the background mesh",
                                 s.file, 100.0 * (1.0 - captured / geometry_volume)));

  FiniteCellStabilisation stabilisation;
  stabilisation.drop_fraction = options.drop_fraction;
  stabilisation.stabilisation = options.stabilisation;
  // A simplified scene folds the stabilisation into its simplified rules (at most
  // C(m+3, 3) points per cut cell, finite_cell_quadrature.hpp).
  if (options.simplify) stabilisation.simplify_degree = cells_.stiffness_degree;
  const StabilisedCells stabilised = stabilise_finite_cells(background, cells_, stabilisation);
  // Points the cut cells assemble with, stabilisation included.
  long long stiffness_in_use = 0, mass_in_use = 0;
  for (int e = 0; e < ne; ++e)
    if (cells_.points_before[e] > 0) {
      stiffness_in_use += cells_.rules[e]->rule.size();
      mass_in_use += cells_.mass_rules[e]->rule.size();
    }

  // The surface, located in the cells that integrate something (null = uncut).
  surface_ = boundary_surface(geometry);
  active_ = finite_cell_active(cells_.volume_fraction, options.drop_fraction);
  try {
    surface_map_ = locate_embedded_points(background, surface_.nodes, active_);
  } catch (const std::invalid_argument& e) {  // every cell empty or dropped
    throw SceneError(fmt::format("{}: embedded: {}", s.file, e.what()));
  }
  const int active_count = background.num_nodes() - static_cast<int>(unsupported_nodes(background, cells_.element_rules()).size());

  stats_ = {
      {"geometry",
       {{"tetrahedra", geometry.num_elements()},
        {"volume", geometry_volume},
        {"volume_in_cells", captured},
        {"surface_triangles", surface_.num_elements()},
        {"surface_vertices", surface_.num_nodes()}}},
      {"cells",
       {{"background", ne},
        {"uncut", uncut},
        {"cut", cut},
        {"empty", empty},
        {"dropped", stabilised.dropped.size()},
        {"stabilised", stabilised.stabilised.size()},
        {"stabilisation_folded", stabilised.folded}}},
      {"nodes", {{"active", active_count}, {"inactive", background.num_nodes() - active_count}}},
      {"drop_fraction", options.drop_fraction},
      {"stabilisation", options.stabilisation},
      {"quadrature",
       {{"simplify", options.simplify},
        {"stiffness_degree", cells_.stiffness_degree},
        {"mass_degree", cells_.mass_degree},
        {"mass_points_clipped", cells_.mass_points_clipped},
        {"mass_points_fitted", cells_.mass_points},
        {"mass_fit_failures", cells_.mass_fit_failures},
        {"max_mass_moment_residual", cells_.max_mass_moment_residual},
        {"max_mass_weight_ratio", cells_.max_mass_weight_ratio},
        {"points_before", cells_.points},
        {"points_after", cells_.simplified_points},
        {"stiffness_points_with_stabilisation", stiffness_in_use},
        {"mass_points_with_stabilisation", mass_in_use},
        {"simplification_failures", cells_.simplification_failures},
        {"max_moment_residual", cells_.max_moment_residual},
        {"generation_seconds", cells_.generation_seconds},
        {"simplification_seconds", cells_.simplification_seconds},
        {"stabilisation_simplification_seconds", stabilised.simplification_seconds},
        {"wall_seconds", cells_.wall_seconds}}},
      {"surface_vertices_extrapolated", surface_map_.num_extrapolated},
      {"setup_seconds", std::chrono::duration<double>(Clock::now() - t0).count()}};
}

Eigen::Matrix3Xd SceneEmbedding::surface_displacement(const Eigen::VectorXd& u) const {
  return interpolate_at_points(background_, surface_map_, u);
}

void SceneEmbedding::write_frame(const std::string& dir, const std::string& name, const Eigen::VectorXd& u, double t,
                                 VtuFormat format) {
  write_vtu((std::filesystem::path(dir) / name).string(), surface_, {{"displacement", surface_displacement(u)}}, {},
            format);
  frames_.emplace_back(t, name);
}

void SceneEmbedding::write_pvd(const std::string& dir, const std::string& name) const {
  hofem::write_pvd((std::filesystem::path(dir) / (name + "_surface.pvd")).string(), frames_);
}

EmbeddedGeometry embedded_geometry(const Scene& s, const Mesh& background) {
  const SceneEmbedded& options = s.embedded.value();
  const Mesh geometry = build_embedded_mesh(s);
  const std::vector<Tetrahedron> tets = mesh_tetrahedra(geometry);
  FiniteCellOptions fc;
  fc.stiffness_degree = options.stiffness_degree;  // the degree SceneEmbedding clips at: the same fractions
  std::vector<double> fraction;
  try {
    fraction = finite_cell_volume_fractions(background, tets, fc);
  } catch (const std::invalid_argument& e) {
    throw SceneError(
        fmt::format("{}: mesh: {} (the background of an embedded scene needs affine cells)", s.file, e.what()));
  }
  return {boundary_surface(geometry), finite_cell_active(fraction, options.drop_fraction)};
}

}  // namespace hofem
