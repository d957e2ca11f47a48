#include "study/scene_error.hpp"

#include <stdexcept>

namespace hofem {

SurfaceLattice run_surface_lattice(const RecordedRun& run, int subdivisions) {
  const int s = subdivisions >= 1 ? subdivisions : default_subdivisions(run.mesh.cell, run.mesh.order);
  if (!run.embedded_surface) return boundary_lattice(run.mesh, s);
  // The embedded surface crosses background cells: even a linear background
  // bends it at cell faces, so at least 2 pieces per triangle.
  return embedded_lattice(run.mesh, *run.embedded_surface, run.active, std::max(2, s));
}

ReferenceMeasure::ReferenceMeasure(const RecordedRun& reference, int subdivisions)
    : reference_(reference) {
  if (reference.embedded_surface && reference.own_rules.empty())
    throw std::invalid_argument("ReferenceMeasure: a finite-cell reference taken from its record needs its mass rules "
                                "(add_own_rules)");
  const int degree = reference.mesh.order + 1;
  quadrature_ = body_quadrature(reference.mesh, degree, reference.own_rules);
  const SurfaceLattice lattice = run_surface_lattice(reference, subdivisions);
  for (const Eigen::VectorXd& u : reference.states) {
    surfaces_.push_back(deformed_surface(reference.mesh, lattice, u));
    values_.push_back(quadrature_.values(reference.mesh, u));
  }
}

std::vector<StateError> scene_error(const RecordedRun& run, const ReferenceMeasure& reference, int subdivisions) {
  if (run.states.size() != reference.run().states.size())
    throw std::invalid_argument("scene_error: the run and the reference recorded different numbers of states");
  const SurfaceLattice lattice = run_surface_lattice(run, subdivisions);
  const EmbeddedPointMap located = locate_embedded_points(run.mesh, reference.quadrature().X, run.active);
  std::vector<StateError> out;
  for (size_t k = 0; k < run.states.size(); ++k) {
    StateError e;
    e.t = run.times[k];
    e.surface = surface_distance(deformed_surface(run.mesh, lattice, run.states[k]), reference.surface(k));
    e.field = field_error(reference.quadrature(), reference.values(k), run.mesh, located, run.states[k]);
    out.push_back(e);
  }
  return out;
}

nlohmann::json to_json(const StateError& e) {
  auto ratio = [](double a, double b) { return b > 0 ? a / b : 0.0; };
  return {{"t", e.t},
          {"surface_rms", e.surface.rms()},
          {"surface_max", e.surface.max()},
          {"surface_rms_run_to_reference", e.surface.a_to_b.rms},
          {"surface_rms_reference_to_run", e.surface.b_to_a.rms},
          {"displacement_rms", e.field.rms()},
          {"l2", e.field.l2},
          {"h1", e.field.h1},
          {"relative_l2", ratio(e.field.l2, e.field.reference_l2)},
          {"relative_h1", ratio(e.field.h1, e.field.reference_h1)},
          {"max_pointwise", e.field.max_pointwise},
          {"extrapolated_volume_fraction", ratio(e.field.extrapolated_volume, e.field.volume)}};
}

}  // namespace hofem
