#pragma once
// The error of a run against a reference run of the same scene, at each
// recorded time (recorded_run.hpp):
//   - surface distance: the RMS and max of the distance between the deformed
//     boundary surfaces, both directions (Longva et al. 2020 §6.2's RMS Hausdorff
//     distance; surface_distance.hpp, surface_sampling.hpp); at t = 0 it is the
//     faceting floor, the run's geometric error before any deformation;
//   - L2 and H1 displacement error over the reference's body (field_error.hpp).
// The reference's measuring data (surfaces, quadrature) is built once and used
// for every run it is compared with.
#include "study/field_error.hpp"
#include "study/recorded_run.hpp"
#include "study/surface_distance.hpp"
#include "study/surface_sampling.hpp"

#include <nlohmann/json.hpp>

#include <vector>

namespace hofem {

/// Subdivisions of faces: < 1 chooses default_subdivisions (surface_sampling.hpp).
SurfaceLattice run_surface_lattice(const RecordedRun& run, int subdivisions);

class ReferenceMeasure {
 public:
  /// The reference's surfaces at its recorded times and its body quadrature:
  /// degree p + 1 in standard elements (the integrand |u_run - u_ref|^2 has kinks
  /// at the run's element faces, which no degree integrates exactly; p + 1
  /// resolves the reference's own variation and halves the points of 2 p), a
  /// finite-cell reference's mass rules in its cut cells.
  ReferenceMeasure(const RecordedRun& reference, int subdivisions);
  ReferenceMeasure(RecordedRun&&, int) = delete;  // kept by reference: a temporary would dangle
  const RecordedRun& run() const { return reference_; }
  const BodyQuadrature& quadrature() const { return quadrature_; }
  const TriangleSurface& surface(size_t state) const { return surfaces_.at(state); }
  /// The reference's displacement and gradient at its quadrature points.
  const PointValues& values(size_t state) const { return values_.at(state); }

 private:
  const RecordedRun& reference_;
  BodyQuadrature quadrature_;
  std::vector<TriangleSurface> surfaces_;
  std::vector<PointValues> values_;
};

/// Names how scene_error measures: a study's stored measurements are keyed by it
/// (recorded_run.hpp: StoredMeasure), so a change to what scene_error computes
/// must change this name, and every stored measurement is then taken again.
inline constexpr const char* kSceneErrorMethod = "scene_error-1";

struct StateError {
  double t = 0;
  SurfaceDistance surface;
  FieldError field;
};

/// The run's error at each of its recorded states against the reference's state
/// of the same index (the same requested time).
std::vector<StateError> scene_error(const RecordedRun& run, const ReferenceMeasure& reference, int subdivisions);

/// {"t", "surface_rms", "surface_max", "surface_rms_run_to_reference",
///  "surface_rms_reference_to_run", "displacement_rms", "l2", "h1", "relative_l2",
///  "relative_h1", "max_pointwise", "extrapolated_volume_fraction"}
nlohmann::json to_json(const StateError& e);

}  // namespace hofem
