#pragma once
// L2 and H1 displacement error of a run against a reference run over the
// reference's body, at the reference's quadrature points:
//   e_L2^2 = sum_q w_q |u_run(X_q) - u_ref(X_q)|^2,
//   e_H1^2 = sum_q w_q |grad u_run(X_q) - grad u_ref(X_q)|_F^2   (the seminorm),
// gradients with respect to the undeformed coordinates X. The run's field is
// evaluated where the reference's points lie in the run's mesh (point location,
// embedded/embedded_points.hpp). A point outside the run's domain (a coarse
// mesh's faceted boundary, a finite cell dropped) is given the run's field
// extrapolated from the nearest cell - the rule of Longva et al. 2020 §5.3 for
// embedded vertices - and the volume of such points is reported, so a reader
// can see how much of the error comes from outside the run's body.
#include "basis/basis_tabulation.hpp"
#include "embedded/embedded_points.hpp"
#include "mesh/mesh.hpp"

#include <Eigen/Core>

#include <memory>
#include <vector>

namespace hofem {


/// Quadrature points over a run's body, located in its mesh: the standard rule
/// of the given degree in every element, or (a finite-cell run) each element's
/// own rule where it has one (null entry = the standard rule, no points = the
/// cell integrates nothing).
struct BodyQuadrature {
  Eigen::Matrix3Xd X;    ///< undeformed positions
  Eigen::VectorXd w;     ///< physical weights (reference weight x |det J|)
  EmbeddedPointMap at;   ///< element and xi in the body's own mesh
  std::vector<Eigen::Matrix3d> J_inverse;  ///< dxi/dX at each point, for the gradients of every state
  int degree = 0;
  std::vector<std::shared_ptr<const ElementQuadrature>> own_rules;
  double volume() const { return w.sum(); }
  /// u and grad u at the points from the body's mesh, element by element with
  /// the rules' tabulated bases (no per-point basis evaluation).
  PointValues values(const Mesh& mesh, const Eigen::VectorXd& u) const;
};
BodyQuadrature body_quadrature(const Mesh& mesh, int degree,
                               const std::vector<std::shared_ptr<const ElementQuadrature>>& own_rules = {});

struct FieldError {
  double l2 = 0, h1 = 0;                   ///< of u_run - u_ref
  double reference_l2 = 0, reference_h1 = 0;  ///< norms of u_ref (relative errors)
  double max_pointwise = 0;                ///< max_q |u_run - u_ref|
  double volume = 0;                       ///< sum of the weights
  double extrapolated_volume = 0;          ///< of the points outside the run's domain
  /// The RMS displacement error sqrt(e_L2^2 / volume): a length, like the surface distance.
  double rms() const;
};

/// The run's field at the reference's points against the reference's values
/// there (q.values(reference mesh, u_reference), computed once per reference state); `run_points` from locate_embedded_points(run_mesh, q.X, active).
FieldError field_error(const BodyQuadrature& q, const PointValues& reference, const Mesh& run_mesh,
                       const EmbeddedPointMap& run_points, const Eigen::VectorXd& u_run);

}  // namespace hofem
