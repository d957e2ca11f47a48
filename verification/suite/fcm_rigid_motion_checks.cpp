// Longva et al. 2020 Fig. 6 (§6.1): a body spinning about its centre of mass. The
// finite cell method integrates the exact (embedded) geometry, so even one
// coarse background cell has the body's mass and centre of mass; a coarse
// boundary-conforming mesh approximates the geometry and with it the centre of
// mass, so the same initial velocity field carries momentum and its centre of
// mass drifts.
//
// Body: half of a tube (r in [0.5, 1], theta in [0, pi], z in [0, 0.3]), whose
// centre of mass is off its bounding box's centre. Ground truth: a fine Tet4
// mesh of it (32 segments on the half circle). Coarse FEM: 3 segments. FCM: the
// fine mesh embedded in one Hex8 cell, one Hex20 cell, and a 4 x 2 x 1 Hex8 grid
// (stabilised, §5.3). All start with v = omega x (X - c_fine) (omega = 2 pi / s
// about z) and run 50 implicit Euler steps of 0.01 s (half a turn) with the
// consistent mass. Implicit Euler conserves linear momentum exactly (internal
// forces sum to zero), so each centre of mass moves on a line at p / m: zero for
// the embedded bodies, omega x (c_coarse - c_fine) for the coarse mesh.
#include "fcm_rigid_motion_checks.hpp"

#include "assembly/assembler.hpp"
#include "dynamics/dynamic_elasticity.hpp"
#include "embedded/embedded_quadrature.hpp"
#include "embedded/finite_cell_quadrature.hpp"
#include "material/material.hpp"
#include "mesh/box_mesh.hpp"
#include "mesh/tube_mesh.hpp"

#include <Eigen/Geometry>
#include <fmt/format.h>

#include <array>
#include <cmath>
#include <string>
#include <vector>

namespace hofem::verification {

namespace {

constexpr double kOmega = 2.0 * M_PI, kDensity = 1000.0, kDt = 0.01;
constexpr int kSteps = 50;

/// The elements of `mesh` with centroid y > 0, on their own nodes.
Mesh upper_half(const Mesh& mesh) {
  std::vector<int> keep, new_id(mesh.num_nodes(), -1), old_id;
  for (int e = 0; e < mesh.num_elements(); ++e) {
    double y = 0.0;
    for (int i = 0; i < mesh.nodes_per_element(); ++i) y += mesh.nodes(1, mesh.elements(i, e));
    if (y > 0.0) keep.push_back(e);
  }
  Mesh half;
  half.cell = mesh.cell;
  half.order = mesh.order;
  half.elements.resize(mesh.nodes_per_element(), static_cast<Eigen::Index>(keep.size()));
  for (size_t k = 0; k < keep.size(); ++k)
    for (int i = 0; i < mesh.nodes_per_element(); ++i) {
      int& id = new_id[mesh.elements(i, keep[k])];
      if (id < 0) {
        id = static_cast<int>(old_id.size());
        old_id.push_back(mesh.elements(i, keep[k]));
      }
      half.elements(i, static_cast<Eigen::Index>(k)) = id;
    }
  half.nodes.resize(3, static_cast<Eigen::Index>(old_id.size()));
  for (size_t n = 0; n < old_id.size(); ++n) half.nodes.col(static_cast<Eigen::Index>(n)) = mesh.nodes.col(old_id[n]);
  return half;
}

Mesh half_tube(int n_theta_half, int n_r) {
  return upper_half(hollow_cylinder_mesh(0.5, 1.0, 0.3, n_r, 2 * n_theta_half, 1, CellType::Tetrahedron, 1));
}

struct Spin {
  Eigen::Vector3d c0, c_end;  ///< centre of mass at start and end
  double mass = 0.0;
  int newton = 0;
  int converged_steps = 0;  ///< steps whose Newton solve converged (a failed step ends the run)
  std::string message;      ///< the failed step's, if any
};

/// Spins `mesh` (with finite-cell rules if given) about c_fine and tracks the
/// centre of mass 1^T M x / 1^T M 1 of the consistent mass.
Spin spin(const Mesh& mesh, const ElementRules& rules, const Eigen::Vector3d& c_fine, const Material& material) {
  DynamicsOptions o;
  o.integrator = Integrator::ImplicitEuler;
  o.dt = kDt;
  o.density = kDensity;
  o.element_rules = rules;
  DynamicElasticity body(mesh, material, {}, o);
  const Eigen::Vector3d omega(0.0, 0.0, kOmega);
  body.set_velocity([&](const Eigen::Vector3d& X) { return Eigen::Vector3d(omega.cross(X - c_fine)); });
  const DofMap all(mesh.num_nodes(), {});
  Assembler mass(mesh, all);
  mass.set_element_rules(rules);
  Eigen::VectorXd ones(3 * mesh.num_nodes());
  for (int n = 0; n < mesh.num_nodes(); ++n) ones.segment<3>(3 * n) = Eigen::Vector3d::Ones();
  const Eigen::VectorXd M1 = mass.mass_action(kDensity, 2 * mesh.order, ones);
  auto centre = [&](const Eigen::VectorXd& x) {
    const Eigen::VectorXd Mx = mass.mass_action(kDensity, 2 * mesh.order, x);
    Eigen::Vector3d m = Eigen::Vector3d::Zero(), mx = Eigen::Vector3d::Zero();
    for (int n = 0; n < mesh.num_nodes(); ++n) {
      m += M1.segment<3>(3 * n);
      mx += Mx.segment<3>(3 * n);
    }
    return Eigen::Vector3d(mx.cwiseQuotient(m));
  };
  Spin s;
  s.c0 = centre(body.positions());
  s.mass = M1.sum() / 3.0;
  for (int k = 0; k < kSteps; ++k) {
    const StepReport r = body.step();
    s.newton += r.newton_iterations;
    if (!r.ok) {
      s.message = r.message;
      break;
    }
    ++s.converged_steps;
  }
  s.c_end = centre(body.positions());
  return s;
}

}  // namespace

void add_fcm_rigid_motion_checks(Report& report) {
  const std::string group = "embedded.fig6";
  const auto material = make_material("neohookean", LameParameters::from_young_poisson(1e7, 0.3));
  const Mesh fine = half_tube(32, 2), coarse = half_tube(3, 1);
  const ElementRules conforming;
  const Spin truth = spin(fine, conforming, Eigen::Vector3d::Zero(), *material);  // c0 of the fine mesh
  const Eigen::Vector3d c_fine = truth.c0;
  const Spin reference = spin(fine, conforming, c_fine, *material);
  const double size = 2.0;  // the body's diameter
  const double t_end = kSteps * kDt;
  report.measure(group, "fine FEM centre of mass y", c_fine.y(), "exact half-annulus: 4 (r2^3 - r1^3) / (3 pi (r2^2 - r1^2)) = 0.4951");
  // Implicit Euler conserves momentum to the Newton tolerance (1e-8 relative
  // forces here, integrated over 50 steps): 1e-6 of the size is far above that
  // and far below the coarse mesh's drift.
  report.check(group, "fine FEM centre-of-mass drift / size", (reference.c_end - reference.c0).norm() / size, 1e-6,
               Compare::AtMost, "zero momentum: the centre of mass stays (Newton tolerance over 50 steps)");

  // The coarse conforming mesh: its own centre of mass is off, so it drifts at
  // |omega x (c_coarse - c_fine)|; the check is that it does, by that amount.
  const Spin c = spin(coarse, conforming, c_fine, *material);
  const double predicted = kOmega * (c.c0 - c_fine).head<2>().norm() * t_end;
  const double drift = (c.c_end - c.c0).norm();
  report.measure(group, "coarse FEM centre-of-mass offset / size", (c.c0 - c_fine).norm() / size,
                 "3 chords per half circle");
  report.check(group, "coarse FEM drift / predicted omega |c_coarse - c_fine| t", drift / predicted, 0.99,
               Compare::AtLeast, "momentum m omega x (c_coarse - c_fine) is conserved: the drift is that exactly");
  report.check(group, "coarse FEM centre-of-mass drift / size", drift / size, 1e-3, Compare::AtLeast,
               "the coarse geometry's error is visible (Longva et al.'s Fig. 6 top right)");

  struct Case {
    const char* name;
    BoxSpec grid;
    int order;
    bool stabilise;
  };
  const std::array<double, 3> lo{-1.0, 0.0, 0.0}, hi{1.0, 1.0, 0.3};  // the body's bounding box
  const std::vector<Tetrahedron> geometry = mesh_tetrahedra(fine);
  for (const Case& k : {Case{"FCM Hex8, 1 cell", {lo, hi, {1, 1, 1}}, 1, false},
                        Case{"FCM Hex20, 1 cell", {lo, hi, {1, 1, 1}}, 2, false},
                        Case{"FCM Hex8, 4x2x1 cells", {lo, hi, {4, 2, 1}}, 1, true}}) {
    const Mesh background = box_mesh(k.grid, CellType::Hexahedron, k.order);
    CellQuadrature fc = finite_cell_quadrature(background, geometry);
    const int stabilised = k.stabilise ? static_cast<int>(stabilise_finite_cells(background, fc).stabilised.size()) : 0;
    const Spin s = spin(background, fc.element_rules(), c_fine, *material);
    // Mass rules integrate the embedded mesh exactly: 1e-12 (rounding). With
    // stabilisation each stabilised cell gains exactly 1e-6 of its full mass
    // (equal cells here), which the check subtracts before comparing.
    const double cell_volume = 2.0 * 1.0 * 0.3 / background.num_elements(), body_volume = truth.mass / kDensity;
    const double added = 1e-6 * stabilised * cell_volume / body_volume;
    report.check(group, fmt::format("{}: mass / fine mass - 1 - stabilisation mass", k.name),
                 std::abs(s.mass / truth.mass - 1.0 - added), 1e-12, Compare::AtMost,
                 fmt::format("exact mass rules (rounding); {} stabilised cells add {:.3g} of the mass", stabilised, added));
    const double mass_tol = added + 1e-12;
    report.check(group, fmt::format("{}: centre-of-mass offset / size", k.name), (s.c0 - c_fine).norm() / size,
                 mass_tol, Compare::AtMost, "the embedded geometry's centre of mass, up to the stabilisation mass");
    // Drift: the momentum of the offset above (omega |offset| t) plus the
    // conforming reference's Newton-level drift.
    report.check(group, fmt::format("{}: centre-of-mass drift / size", k.name), (s.c_end - s.c0).norm() / size,
                 kOmega * t_end * mass_tol + 1e-6, Compare::AtMost,
                 "zero momentum up to the mass rule's error (Longva et al. 2020: FCM keeps the centre of mass)");
    // A count, not a flag: the centre-of-mass rows above are of a run that
    // reached t_end only if every one of its kSteps steps converged.
    report.check(group, fmt::format("{}: all steps converged", k.name), s.converged_steps, kSteps, Compare::AtLeast,
                 fmt::format("implicit Euler steps whose Newton solve converged, of the {} run (half a turn at dt = "
                             "{:g} s; a failed step ends the run){}",
                             kSteps, kDt, s.message.empty() ? "" : ": " + s.message));
  }
}

}  // namespace hofem::verification
