#include "dynamics_checks.hpp"

#include "assembly/assembler.hpp"
#include "material/material.hpp"
#include "mesh/box_mesh.hpp"

#include <Eigen/Eigenvalues>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace hofem::verification {

namespace {

// A linear-elastic bar [0,2]x[0,1]x[0,1] (Tet4, 2x1x1 cells, E = 1e4, nu = 0.3,
// rho = 10) clamped at x = 0, lumped mass: M u'' = -K u has the exact solution
// u(t) = sum_k phi_k (a_k cos w_k t + b_k / w_k sin w_k t). It starts displaced
// along mode 1 and moving along modes 1 and 2; with a zero initial displacement
// (zero initial force) symplectic Euler would coincide with leapfrog (order 2).
struct Bar {
  Mesh mesh = box_mesh(BoxSpec{{0, 0, 0}, {2, 1, 1}, {2, 1, 1}}, CellType::Tetrahedron, 1);
  std::unique_ptr<Material> material = make_material("linear", LameParameters::from_young_poisson(1e4, 0.3));
  double rho = 10.0;
  DofMap dofs{mesh.num_nodes(), mesh.node_set("xmin")};
  Eigen::VectorXd omega, u0, v0, a, b;  // frequencies, initial state, modal coefficients
  Eigen::MatrixXd Phi;                  // M-orthonormal modes over the free DOFs
  Bar() {
    const Assembler as(mesh, dofs);
    SparseMatrix K = as.new_matrix();
    Eigen::VectorXd g;
    as.hessian(*material, Eigen::Map<const Eigen::VectorXd>(mesh.nodes.data(), 3 * mesh.num_nodes()), g, K, false);
    const Eigen::VectorXd m = dofs.restrict(as.lumped_mass(rho, 2, MassLumping::RowSum));
    const Eigen::VectorXd s = m.cwiseSqrt().cwiseInverse();
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(s.asDiagonal() * Eigen::MatrixXd(K) * s.asDiagonal());
    omega = eig.eigenvalues().cwiseSqrt();
    Phi = s.asDiagonal() * eig.eigenvectors();
    u0 = 1e-3 * Phi.col(0) / omega[0];
    v0 = 1e-3 * (Phi.col(0) + 0.3 * Phi.col(1));
    // a = Phi^T M u0 = Phi^-1 u0, b = Phi^-1 v0 (Phi^T M Phi = I).
    const auto qr = Phi.colPivHouseholderQr();
    a = qr.solve(u0);
    b = qr.solve(v0);
  }
  Eigen::VectorXd exact(double t) const {
    Eigen::VectorXd u = Eigen::VectorXd::Zero(Phi.rows());
    for (Eigen::Index k = 0; k < Phi.cols(); ++k)
      u += Phi.col(k) * (a[k] * std::cos(omega[k] * t) + b[k] / omega[k] * std::sin(omega[k] * t));
    return u;
  }
  double period() const { return 2.0 * M_PI / omega[0]; }
};

const Bar& bar() {
  static const Bar b;
  return b;
}

}  // namespace

double bar_vibration_error(Integrator integrator, int steps) {
  const Bar& B = bar();
  DynamicsOptions o;
  o.integrator = integrator;
  o.density = B.rho;
  o.mass = MassKind::Lumped;
  // Not a whole period: there symplectic Euler's O(h) phase term vanishes.
  o.dt = 0.75 * B.period() / steps;
  o.newton.rtol = 1e-10;  // Newton's error 1e-10 of the force scale, far below O(h) ~ 1e-3
  DynamicElasticity sim(B.mesh, *B.material, {fixed_nodes(B.mesh.node_set("xmin"))}, o);
  Eigen::VectorXd x = sim.positions(), v = Eigen::VectorXd::Zero(x.size());
  B.dofs.add_free(B.u0, x);
  B.dofs.add_free(B.v0, v);
  sim.set_positions(x);
  sim.set_velocities(v);
  for (int k = 0; k < steps; ++k)
    if (!sim.step().ok) return std::numeric_limits<double>::quiet_NaN();
  const Eigen::VectorXd ue = B.exact(sim.time());
  return (B.dofs.restrict(sim.displacement()) - ue).norm() / ue.norm();
}

FreeBody::FreeBody()
    : mesh(box_mesh(unit_cube(2), CellType::Tetrahedron, 1)),
      material(make_material("neohookean", LameParameters::from_young_poisson(1e4, 0.3))) {}

std::unique_ptr<DynamicElasticity> FreeBody::simulation(Integrator integrator, double dt) const {
  DynamicsOptions o;
  o.integrator = integrator;
  o.dt = dt;
  o.density = 100.0;
  o.mass = MassKind::Lumped;
  auto sim = std::make_unique<DynamicElasticity>(mesh, *material, std::vector<PrescribedMotion>{}, o);
  const Eigen::Vector3d w(0.3, -0.5, 1.0), c(0.5, 0.5, 0.5);
  sim->set_velocity([&](const Eigen::Vector3d& X) -> Eigen::Vector3d {
    return Eigen::Vector3d(0.2, 0.1, -0.3) + w.cross(X - c) + Eigen::Vector3d(0.5 * (X.x() - 0.5), 0, 0);
  });
  return sim;
}

namespace {

void add_order_rows(Report& report) {
  for (const std::string& name : integrator_names()) {
    const Integrator integrator = parse_integrator(name);
    const double e1 = bar_vibration_error(integrator, 160), e2 = bar_vibration_error(integrator, 320);
    const double order = std::log2(e1 / e2);
    report.check("dynamics.order", name + " |observed - expected order|", std::abs(order - integrator_order(integrator)),
                 0.2, Compare::AtMost,
                 fmt::format("observed {:.3f}, expected {}; errors {:.3e} at h = 0.75 T/160, {:.3e} at T/320 (h w_max <= "
                             "0.5): asymptotic rate, 0.2 for the next term of the error expansion",
                             order, integrator_order(integrator), e1, e2));
  }
  const double semi = bar_vibration_error(Integrator::SemiImplicit, 100),
               implicit = bar_vibration_error(Integrator::ImplicitEuler, 100);
  report.check("dynamics.order", "semi-implicit = implicit Euler on a linear material", std::abs(semi - implicit) / implicit,
               1e-6, Compare::AtMost,
               "Baraff-Witkin is backward Euler's Newton step, exact in one iteration for a quadratic energy; equal up "
               "to Newton's tolerance 1e-10 of the force scale");
}

void add_momentum_rows(Report& report) {
  const FreeBody body;
  for (const std::string& name : integrator_names()) {
    const Integrator integrator = parse_integrator(name);
    auto sim = body.simulation(integrator, 1e-3);
    const Eigen::Vector3d P0 = sim->linear_momentum(), L0 = sim->angular_momentum();
    bool ok = true;
    for (int k = 0; k < 200 && ok; ++k) ok = sim->step().ok;
    const double dP = ok ? (sim->linear_momentum() - P0).norm() / P0.norm() : std::numeric_limits<double>::quiet_NaN();
    const double dL = ok ? (sim->angular_momentum() - L0).norm() / L0.norm() : std::numeric_limits<double>::quiet_NaN();
    report.check("dynamics.momentum", name + " linear momentum, 200 steps", dP, 1e-12, Compare::AtMost,
                 "internal forces sum to zero (translation invariance): conserved to rounding");
    if (integrator == Integrator::SymplecticEuler || integrator == Integrator::Leapfrog)
      report.check("dynamics.momentum", name + " angular momentum, 200 steps", dL, 1e-11, Compare::AtMost,
                   "variational integrator, rotation-invariant energy, isotropic nodal masses: x_n+1 x m v_n+1 = "
                   "x_n x m v_n+1 and sum x x f = 0, so exact up to rounding");
    else
      report.measure("dynamics.momentum", name + " angular momentum drift, 200 steps", dL,
                     "not conserved exactly by this scheme (O(h) for the first-order ones)");
  }
}

void add_energy_rows(Report& report) {
  const FreeBody body;
  for (Integrator integrator : {Integrator::SymplecticEuler, Integrator::Leapfrog}) {
    auto sim = body.simulation(integrator, 1e-3);
    const double stable = sim->estimate_stable_dt();
    const int steps = 4000;
    std::vector<double> E;
    for (int k = 0; k < steps; ++k) {
      if (!sim->step().ok) break;
      E.push_back(sim->energies().total());
    }
    double first = 0.0, last = 0.0, spread = 0.0;
    const int q = steps / 4;
    const bool complete = static_cast<int>(E.size()) == steps;
    for (int k = 0; complete && k < q; ++k) first += E[k] / q, last += E[steps - 1 - k] / q;
    const double E0 = complete ? E.front() : std::numeric_limits<double>::quiet_NaN();
    for (double e : E) spread = std::max(spread, std::abs(e - E0) / E0);
    const std::string name(integrator_name(integrator));
    report.check("dynamics.energy", name + " drift, mean of last vs first quarter of 4000 steps",
                 complete ? std::abs(last - first) / E0 : std::numeric_limits<double>::quiet_NaN(), 0.01,
                 Compare::AtMost,
                 fmt::format("symplectic: a modified energy is conserved, so no secular drift; dt = 1e-3 = {:.2f} of "
                             "the stable dt",
                             1e-3 / stable));
    report.check("dynamics.energy", name + " max |E - E0| / E0 over 4000 steps", complete ? spread : NAN, 0.02,
                 Compare::AtMost,
                 fmt::format("the modified energy differs from E by O((h w)^2); h w_max = {:.2f} here", 2e-3 / stable));
  }
  auto sim = body.simulation(Integrator::ImplicitEuler, 1e-3);
  double previous = sim->energies().total(), worst = -std::numeric_limits<double>::infinity();
  const double E0 = previous;
  for (int k = 0; k < 200; ++k) {
    if (!sim->step().ok) {
      worst = NAN;
      break;
    }
    const double e = sim->energies().total();
    worst = std::max(worst, (e - previous) / E0);
    previous = e;
  }
  report.check("dynamics.energy", "implicit-euler largest energy increase per step / E0, 200 steps", worst, 1e-10,
               Compare::AtMost, "backward Euler without forcing only dissipates; 1e-10 for Newton's tolerance");
}

// The explicit integrators' stability limits, from the literature rather than
// from core/dynamics: h omega < 2 for symplectic Euler and leapfrog (their
// amplification matrix on u'' = -omega^2 u has trace 2 - (h omega)^2), and
// h omega < 2 sqrt(2) for classical RK4 (the imaginary-axis interval of its
// stability polynomial 1 + z + z^2/2 + z^3/6 + z^4/24; Hairer & Wanner,
// Solving ODEs II, §IV.2).
struct PublishedLimit {
  Integrator integrator;
  double h_omega;
};
constexpr PublishedLimit kPublishedLimits[] = {{Integrator::SymplecticEuler, 2.0},
                                               {Integrator::Leapfrog, 2.0},
                                               {Integrator::RK4, 2.8284271247461903}};

// The bar, displaced along its lowest and highest modes, run for `steps` steps
// at dt: the largest total energy over the run's last quarter / the initial
// energy (NaN if a step failed). The highest mode is the one that decides
// stability; the lowest keeps the energy from being that mode's alone.
double bar_energy_growth(Integrator integrator, double dt, int steps, double* stable_dt_estimate = nullptr) {
  const Bar& B = bar();
  DynamicsOptions o;
  o.integrator = integrator;
  o.density = B.rho;
  o.mass = MassKind::Lumped;
  o.dt = dt;
  DynamicElasticity sim(B.mesh, *B.material, {fixed_nodes(B.mesh.node_set("xmin"))}, o);
  const Eigen::Index top = B.omega.size() - 1;
  Eigen::VectorXd x = sim.positions();
  B.dofs.add_free(1e-4 * (B.Phi.col(0) / B.omega[0] + B.Phi.col(top) / B.omega[top]), x);
  sim.set_positions(x);
  if (stable_dt_estimate) *stable_dt_estimate = sim.estimate_stable_dt();
  const double E0 = sim.energies().total();
  double late = 0.0;
  for (int k = 0; k < steps; ++k) {
    if (!sim.step().ok) return std::numeric_limits<double>::quiet_NaN();
    if (k >= steps - steps / 4) late = std::max(late, sim.energies().total());
  }
  return late / E0;
}

void add_stability_rows(Report& report) {
  const Bar& B = bar();
  const double omega_max = B.omega.maxCoeff();  // dense eigensolve of the bar's M^-1 K
  for (const PublishedLimit& p : kPublishedLimits) {
    const std::string name(integrator_name(p.integrator));
    const double limit_dt = p.h_omega / omega_max;
    double estimate = 0.0;
    const int steps = 400;
    const double below = bar_energy_growth(p.integrator, 0.98 * limit_dt, steps, &estimate);
    const double above = bar_energy_growth(p.integrator, 1.02 * limit_dt, steps);
    // The code's estimate (its own limit over a 40-step power iteration's
    // omega_max) against the published limit over the exact omega_max. Power
    // iteration approaches omega_max from below, so the estimate can only be
    // larger; on this 2-cell bar it is 4.1e-4 above (measured), and 1e-3
    // leaves 2.4x room for another start vector. Smaller than 0.99 is a limit
    // taken too small (steps refused that are stable).
    const std::string ratio_name = name + " stable dt estimate / (published h omega limit / omega_max)";
    const std::string facts = fmt::format("published limit h omega < {:.4f}, omega_max = {:.4g} from the dense eigensolve",
                                          p.h_omega, omega_max);
    report.check("dynamics.stability", ratio_name, estimate / limit_dt, 0.99, Compare::AtLeast,
                 facts + "; below 0.99 the limit is taken too small (stable steps refused)");
    report.check("dynamics.stability", ratio_name, estimate / limit_dt, 1.001, Compare::AtMost,
                 facts + "; above 1.001 the estimate allows unstable steps");
    // Inside the limit the energy stays bounded: the highest mode's energy
    // under leapfrog oscillates by up to 1 / (1 - (h omega / 2)^2) ~ 25x at
    // 0.98 of the limit, so "bounded" is against growth, 1e3 over 400 steps.
    report.check("dynamics.stability", name + " energy late / initial at 0.98 of the published limit, 400 steps",
                 below, 1e3, Compare::AtMost,
                 "inside the stability interval no mode grows; bounded oscillation of the modified energy only");
    // Just outside it the top mode grows geometrically: |amplification| is
    // >= 1.15 per step for RK4 and >= 1.2 for leapfrog / symplectic Euler at
    // 1.02 of the limit, so 400 steps multiply its energy by far more than 1e6.
    report.check("dynamics.stability", name + " energy late / initial at 1.02 of the published limit, 400 steps",
                 std::isnan(above) ? std::numeric_limits<double>::infinity() : above, 1e6, Compare::AtLeast,
                 "outside the interval the highest mode is amplified every step: the limit is sharp, not just safe "
                 "(a failed step, flagged unstable by the run, counts as growth)");
  }
}

void add_mass_rows(Report& report) {
  struct Case {
    CellType cell;
    int order;
    MassLumping lumping;
    const char* name;
  };
  const double rho = 7.5, volume = 2.0;
  for (const Case c : {Case{CellType::Tetrahedron, 1, MassLumping::RowSum, "Tet4 row-sum"},
                       Case{CellType::Tetrahedron, 2, MassLumping::HRZ, "Tet10 HRZ"},
                       Case{CellType::Tetrahedron, 3, MassLumping::HRZ, "Tet20 HRZ"},
                       Case{CellType::Hexahedron, 1, MassLumping::RowSum, "Hex8 row-sum"},
                       Case{CellType::Hexahedron, 2, MassLumping::HRZ, "Hex20 HRZ"}}) {
    const Mesh m = box_mesh(BoxSpec{{0, 0, 0}, {2, 1, 1}, {3, 2, 2}}, c.cell, c.order);
    const DofMap all(m.num_nodes(), {});
    const Assembler a(m, all);
    const Eigen::VectorXd lumped = a.lumped_mass(rho, 2 * c.order, c.lumping);
    report.check("dynamics.mass", fmt::format("{} total mass relative error", c.name),
                 std::abs(lumped.sum() / 3.0 - rho * volume) / (rho * volume), 1e-13, Compare::AtMost,
                 "a sum of ~1e3 positive terms: rounding");
    report.check("dynamics.mass", fmt::format("{} smallest nodal mass / mean", c.name),
                 lumped.minCoeff() / lumped.mean(), 0.0, Compare::AtLeast,
                 "explicit integrators divide by it: must be positive (row sums of Tet10 / Hex20 are not)");
  }
}

}  // namespace

void add_dynamics_checks(Report& report) {
  add_mass_rows(report);
  add_order_rows(report);
  add_momentum_rows(report);
  add_energy_rows(report);
  add_stability_rows(report);
}

}  // namespace hofem::verification
