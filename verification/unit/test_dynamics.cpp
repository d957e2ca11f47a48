// Dynamics: masses, the convergence order in dt of every integrator
// against the exact modal solution of a linear-elastic bar, energy behaviour,
// momentum conservation, and instability detection of the explicit schemes.
#include "assembly/assembler.hpp"
#include "dynamics/dynamic_elasticity.hpp"
#include "dynamics/mass_model.hpp"
#include "material/material.hpp"
#include "dynamics_checks.hpp"
#include "mesh/box_mesh.hpp"

#include <Eigen/Eigenvalues>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace hofem {
namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();

// ---- masses -------------------------------------------------------------------

// The consistent mass integrates 1 . M 1 = rho V exactly with its degree-2p
// rule (1e-13: rounding of ~1e3 terms), and mass_action applies the same
// operator without the matrix. (Lumped totals and positivity are the suite's
// dynamics.mass rows.)
TEST(Mass, ConsistentMassAndItsMatrixFreeAction) {
  const double rho = 7.5, volume = 2.0;  // box [0,2] x [0,1] x [0,1]
  struct Case {
    CellType cell;
    int order;
  };
  for (const Case c : {Case{CellType::Tetrahedron, 1}, Case{CellType::Tetrahedron, 2}, Case{CellType::Tetrahedron, 3},
                       Case{CellType::Hexahedron, 1}, Case{CellType::Hexahedron, 2}}) {
    const Mesh m = box_mesh(BoxSpec{{0, 0, 0}, {2, 1, 1}, {3, 2, 2}}, c.cell, c.order);
    const DofMap all(m.num_nodes(), {});
    const Assembler a(m, all);
    const SparseMatrix M = a.mass_matrix(rho, 2 * c.order);
    EXPECT_NEAR(Eigen::VectorXd::Ones(M.rows()).dot(M * Eigen::VectorXd::Ones(M.rows())) / 3.0, rho * volume,
                1e-13 * rho * volume);
    Eigen::VectorXd r(M.rows());
    for (Eigen::Index i = 0; i < r.size(); ++i) r[i] = std::sin(0.37 * i);
    EXPECT_LE((a.mass_action(rho, 2 * c.order, r) - M * r).norm(), 1e-13 * (M * r).norm());
  }
  // Row sums of Tet10 put negative mass on the vertices: refused with a reason.
  const Mesh m = box_mesh(unit_cube(1), CellType::Tetrahedron, 2);
  const auto mat = make_material("linear", LameParameters::from_young_poisson(1e3, 0.3));
  DynamicsOptions o;
  o.integrator = Integrator::SymplecticEuler;
  o.lumping = MassLumping::RowSum;
  try {
    DynamicElasticity sim(m, *mat, {}, o);
    FAIL() << "row-sum lumping of Tet10 was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("non-positive nodal mass"), std::string::npos) << e.what();
  }
}

// The nodal mass matrix Ms that dynamics keeps (M = Ms (x) I3 over all nodes)
// against the DOF matrix assembled by the other path (mass_matrix, entry by
// entry into the free-DOF pattern), with a third of the nodes constrained:
// MassModel's free block added into a zero matrix, its products over the free
// and over all DOFs. Both paths sum the same element masses in another order:
// 1e-14 relative is ~50 roundings of the largest entry.
TEST(Mass, NodalMatrixServesEveryConsistentProduct) {
  const double rho = 3.5;
  for (const auto& [cell, order] : {std::pair{CellType::Tetrahedron, 2}, std::pair{CellType::Tetrahedron, 3},
                                    std::pair{CellType::Hexahedron, 2}}) {
    const Mesh m = box_mesh(BoxSpec{{0, 0, 0}, {2, 1, 1}, {3, 2, 2}}, cell, order);
    std::vector<int> fixed;
    for (int v = 0; v < m.num_nodes(); v += 3) fixed.push_back(v);
    Discretization disc(m, false, {}, -1);
    disc.constrain(fixed);
    const MassModel mass(disc, rho, MassKind::Consistent, MassLumping::RowSum, 2 * order, -1, false);
    const SparseMatrix M = disc.assembler().mass_matrix(rho, 2 * order);
    const double scale = Eigen::Map<const Eigen::VectorXd>(M.valuePtr(), M.nonZeros()).cwiseAbs().maxCoeff();
    SparseMatrix K = disc.assembler().new_matrix();
    mass.add_free_to(K, 2.0);
    EXPECT_LE((SparseMatrix(K - 2.0 * M)).coeffs().cwiseAbs().maxCoeff(), 1e-14 * scale);
    Eigen::VectorXd w(M.rows());
    for (Eigen::Index i = 0; i < w.size(); ++i) w[i] = std::cos(0.41 * i);
    EXPECT_LE((mass.free_times(w) - M * w).norm(), 1e-14 * (M * w).norm());
    // All DOFs: against the element-by-element action.
    Eigen::VectorXd r(3 * m.num_nodes());
    for (Eigen::Index i = 0; i < r.size(); ++i) r[i] = std::sin(0.29 * i);
    const Eigen::VectorXd expected = disc.assembler().mass_action(rho, 2 * order, r);
    EXPECT_LE((mass.consistent_times(r) - expected).norm(), 1e-14 * expected.norm());
    EXPECT_NEAR(mass.min_diagonal(), M.diagonal().minCoeff(), 1e-14 * scale);
  }
}

// ---- convergence order in dt ---------------------------------------------------

using verification::bar_vibration_error;
using verification::FreeBody;

// Observed order log2(e(h) / e(h/2)) at h = 0.75 T/160 -> 0.75 T/320 (T the lowest
// period; h w_max <= 0.5 there) must be the scheme's order within 0.2: the
// asymptotic rate, with room for the next term of the error expansion.
TEST(Integrators, ConvergeAtTheirOrderInDt) {
  for (const std::string& name : integrator_names()) {
    const Integrator integrator = parse_integrator(name);
    const double e1 = bar_vibration_error(integrator, 160), e2 = bar_vibration_error(integrator, 320);
    const double order = std::log2(e1 / e2);
    EXPECT_NEAR(order, integrator_order(integrator), 0.2) << name << ": errors " << e1 << ", " << e2;
    RecordProperty(name + "_order", std::to_string(order));
    std::printf("%s: errors %.3e %.3e order %.3f\n", name.c_str(), e1, e2, order);
  }
}

// For a linear material Baraff-Witkin's linearised step is backward Euler's
// Newton step on a quadratic, exact in one iteration: the two integrators give
// the same trajectory up to Newton's tolerance (1e-10 of the force scale).
TEST(Integrators, SemiImplicitIsBackwardEulerOnALinearMaterial) {
  const double a = bar_vibration_error(Integrator::SemiImplicit, 100),
               b = bar_vibration_error(Integrator::ImplicitEuler, 100);
  EXPECT_NEAR(a, b, 1e-6 * b);
}

// ---- energy and momentum -------------------------------------------------------

// Internal forces sum to zero (each element's forces do, translation
// invariance), so M v changes by sum(f) = 0 every step: conserved to rounding,
// |dP| <= 1e-12 |P| (a sum of ~1e2 terms of size |P| per step, 200 steps). Angular
// momentum: symplectic Euler and leapfrog are variational integrators with a
// rotation-invariant potential and isotropic nodal masses, so x x M v is exactly
// conserved (x_{n+1} x m v_{n+1} = x_n x m v_{n+1} and sum x_n x f(x_n) = 0);
// 1e-11 relative allows rounding over 200 steps. Explicit Euler, RK4 and the
// implicit schemes do not conserve it exactly: asserted only to shrink with dt.
TEST(Dynamics, MomentumOfAFreeBody) {
  const FreeBody body;
  for (const std::string& name : integrator_names()) {
    const Integrator integrator = parse_integrator(name);
    auto sim = body.simulation(integrator, 1e-3);
    const Eigen::Vector3d P0 = sim->linear_momentum(), L0 = sim->angular_momentum();
    for (int k = 0; k < 200; ++k) ASSERT_TRUE(sim->step().ok) << name;
    EXPECT_LE((sim->linear_momentum() - P0).norm(), 1e-12 * P0.norm()) << name;
    const double dL = (sim->angular_momentum() - L0).norm() / L0.norm();
    if (integrator == Integrator::SymplecticEuler || integrator == Integrator::Leapfrog) {
      EXPECT_LE(dL, 1e-11) << name;
    } else {
      auto half = body.simulation(integrator, 5e-4);
      for (int k = 0; k < 400; ++k) ASSERT_TRUE(half->step().ok) << name;
      const double dL_half = (half->angular_momentum() - L0).norm() / L0.norm();
      EXPECT_LT(dL_half, dL) << name << ": angular momentum drift " << dL << " at dt and " << dL_half << " at dt/2";
    }
    std::printf("%s: |dP|/|P| = %.2e, |dL|/|L| = %.2e\n", name.c_str(), (sim->linear_momentum() - P0).norm() / P0.norm(), dL);
  }
}

// Symplectic schemes keep the energy of the free body bounded over a long run
// (no drift): the mean over the last quarter stays within 1 % of the first
// quarter's, and the oscillation within 2 % of E0 (h w_max ~ 0.5: the modified
// energy differs from E by O((h w)^2)). Backward Euler without forcing only
// dissipates: E(t) never increases (allowing 1e-10 relative for Newton's tolerance).
TEST(Dynamics, EnergyBoundedForSymplecticAndDecayingForImplicitEuler) {
  const FreeBody body;
  for (Integrator integrator : {Integrator::SymplecticEuler, Integrator::Leapfrog}) {
    auto sim = body.simulation(integrator, 1e-3);
    const double stable = sim->estimate_stable_dt();
    ASSERT_LT(1e-3, 0.5 * stable) << "the run must be well inside the stable range";
    const int steps = 4000;
    std::vector<double> E;
    for (int k = 0; k < steps; ++k) {
      ASSERT_TRUE(sim->step().ok);
      E.push_back(sim->energies().total());
    }
    double first = 0.0, last = 0.0, spread = 0.0;
    for (int k = 0; k < steps / 4; ++k) first += E[k] / (steps / 4), last += E[steps - 1 - k] / (steps / 4);
    const double E0 = E.front();
    for (double e : E) spread = std::max(spread, std::abs(e - E0) / E0);
    EXPECT_LE(std::abs(last - first), 0.01 * E0) << integrator_name(integrator);
    EXPECT_LE(spread, 0.02) << integrator_name(integrator);
    std::printf("%s: energy drift (last - first quarter) %.2e, max |E - E0|/E0 %.2e\n",
                std::string(integrator_name(integrator)).c_str(), std::abs(last - first) / E0, spread);
  }
  auto sim = body.simulation(Integrator::ImplicitEuler, 1e-3);
  double previous = sim->energies().total();
  const double E0 = previous;
  for (int k = 0; k < 200; ++k) {
    ASSERT_TRUE(sim->step().ok);
    const double e = sim->energies().total();
    EXPECT_LE(e, previous + 1e-10 * E0) << "step " << k;
    previous = e;
  }
  EXPECT_LT(previous, E0);
}

// Explicit integration with the consistent mass: one Cholesky factor of M for
// the whole run and no Hessian; momentum (sum of M v) is still conserved since
// the rows of M sum to the nodal masses and the internal forces to zero.
TEST(Dynamics, ExplicitWithConsistentMass) {
  const FreeBody body;
  DynamicsOptions o;
  o.integrator = Integrator::Leapfrog;
  o.dt = 5e-4;
  o.density = 100.0;
  o.mass = MassKind::Consistent;
  DynamicElasticity sim(body.mesh, *body.material, {}, o);
  sim.set_velocity([](const Eigen::Vector3d& X) -> Eigen::Vector3d { return Eigen::Vector3d(0.2, 0.5 * X.x(), -0.3); });
  const Eigen::Vector3d P0 = sim.linear_momentum();
  const double E0 = sim.energies().total();
  for (int k = 0; k < 200; ++k) ASSERT_TRUE(sim.step().ok);
  EXPECT_LE((sim.linear_momentum() - P0).norm(), 1e-12 * P0.norm());
  EXPECT_NEAR(sim.energies().total(), E0, 0.02 * E0);  // symplectic: bounded, as in the lumped case
  EXPECT_EQ(sim.stats().mass_factorizations, 1);
  EXPECT_EQ(sim.stats().hessian_assemblies, 0);
  EXPECT_EQ(sim.stats().mass, "consistent");
}

// ---- stability ------------------------------------------------------------------

// Above the stable dt an explicit scheme stops with a report naming the stable
// dt instead of writing NaN; the state stays at the last good step. Below it,
// the same run is fine.
TEST(Dynamics, ExplicitSchemesDetectInstability) {
  const FreeBody body;
  for (Integrator integrator : {Integrator::SymplecticEuler, Integrator::Leapfrog, Integrator::RK4}) {
    auto probe = body.simulation(integrator, 1e-3);
    const double stable = probe->estimate_stable_dt();
    auto good = body.simulation(integrator, 0.5 * stable);
    for (int k = 0; k < 300; ++k) {
      const StepReport g = good->step();
      ASSERT_TRUE(g.ok) << integrator_name(integrator) << " at 0.5 x the stable dt " << stable << ": " << g.message;
    }
    auto bad = body.simulation(integrator, 3.0 * stable);
    StepReport r;
    int k = 0;
    for (; k < 5000 && (r = bad->step()).ok; ++k) {
    }
    ASSERT_FALSE(r.ok) << integrator_name(integrator) << " ran 5000 steps at 3x the stable dt";
    EXPECT_NE(r.message.find("unstable"), std::string::npos) << r.message;
    EXPECT_NE(r.message.find("needs "), std::string::npos) << r.message;
    EXPECT_TRUE(bad->positions().allFinite() && bad->velocities().allFinite());
    std::printf("%s: stable dt %.3e; at 3x it stopped after %d steps: %s\n",
                std::string(integrator_name(integrator)).c_str(), stable, k, r.message.c_str());
  }
  // Explicit Euler has no stable dt without damping: reported as such, and the
  // stopped run says what helps instead of naming a bound "dt < 0".
  auto euler = body.simulation(Integrator::ExplicitEuler, 1e-3);
  EXPECT_EQ(euler->estimate_stable_dt(), 0.0);
  StepReport r;
  int k = 0;
  for (; k < 20000 && (r = euler->step()).ok; ++k) {
  }
  ASSERT_FALSE(r.ok) << "explicit Euler ran 20000 undamped steps";
  EXPECT_NE(r.message.find("amplifies every undamped mode at any dt"), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("damping"), std::string::npos) << r.message;
  EXPECT_EQ(r.message.find("dt <"), std::string::npos) << r.message;
  EXPECT_TRUE(euler->positions().allFinite() && euler->velocities().allFinite());
  std::printf("explicit-euler at dt 1e-3 stopped after %d steps: %s\n", k, r.message.c_str());
}

// ---- stress tests of numerical stability ---------------------------------------

// No element inverted: the Neo-Hookean energy is +infinity where any quadrature
// point has det F <= 0, finite otherwise.
bool no_inversion(const Assembler& a, const Eigen::VectorXd& x) {
  const auto nh = make_material("neohookean", LameParameters::from_young_poisson(1.0, 0.3));
  return std::isfinite(a.energy(*nh, x));
}

// Implicit Euler at dt = 1/30 on a stiff, nearly incompressible cantilever
// (E = 1e8, nu = 0.49, Stable Neo-Hookean, Tet10) under gravity: every step
// converges, nothing is NaN, nothing inverts, and the tip stays near the
// static deflection scale (it cannot run away).
TEST(StressTests, ImplicitEulerStiffNearlyIncompressibleCantilever) {
  const Mesh m = box_mesh(BoxSpec{{0, 0, 0}, {4, 1, 1}, {4, 1, 1}}, CellType::Tetrahedron, 2);
  const auto mat = make_material("stable-neohookean", LameParameters::from_young_poisson(1e8, 0.49));
  DynamicsOptions o;
  o.dt = 1.0 / 30.0;
  o.density = 1000.0;
  o.gravity = Eigen::Vector3d(0, 0, -9.81);
  o.solver = SolverSpec::parse("cholmod");  // the symbolic-analysis count below is a direct solver's
  DynamicElasticity sim(m, *mat, {fixed_nodes(m.node_set("xmin"))}, o);
  for (int k = 0; k < 30; ++k) {
    const StepReport r = sim.step();
    ASSERT_TRUE(r.ok) << "step " << k << ": " << r.message;
    ASSERT_TRUE(sim.positions().allFinite());
    ASSERT_TRUE(no_inversion(sim.assembler(), sim.positions())) << "step " << k;
  }
  // Euler-Bernoulli static tip deflection rho g A L^4 / (8 E I) = 3.77e-2 m for
  // this beam (A = 1, I = 1/12, L = 4). The dynamic tip starts from rest and can
  // overshoot to at most twice the static value; a coarse Tet10 mesh at nu = 0.49
  // is stiffer (locking), hence the lower bound of 0.1x.
  const double tip = sim.displacement().reshaped(3, m.num_nodes()).row(2).minCoeff();
  EXPECT_LT(std::abs(tip), 2.0 * 3.77e-2) << tip;
  EXPECT_GT(std::abs(tip), 0.1 * 3.77e-2) << tip;
  std::printf("stiff cantilever: tip %.3e m after 1 s, %d Newton iterations, %d Hessians, %d analyses\n", tip,
              sim.stats().newton_iterations, sim.stats().hessian_assemblies, sim.stats().symbolic_analyses);
  EXPECT_EQ(sim.stats().symbolic_analyses, 1);  // one symbolic factorisation for the whole run
}

// Stable Neo-Hookean is defined for inverted elements (det F < 0) and its
// elastic force pushes them back: a cube whose top face is pushed below its
// middle layer (every top element inverted) recovers under implicit Euler.
TEST(StressTests, StableNeoHookeanRecoversFromInvertedElements) {
  const Mesh m = box_mesh(unit_cube(2), CellType::Tetrahedron, 1);
  const auto mat = make_material("stable-neohookean", LameParameters::from_young_poisson(1e5, 0.4));
  DynamicsOptions o;
  o.dt = 1.0 / 60.0;
  o.density = 100.0;
  o.rayleigh_alpha = 1.0;
  DynamicElasticity sim(m, *mat, {fixed_nodes(m.node_set("zmin"))}, o);
  Eigen::VectorXd x = sim.positions();
  for (int i = 0; i < m.num_nodes(); ++i)
    if (m.nodes(2, i) > 0.75) x[3 * i + 2] = 0.3;  // the top face below the middle layer (z = 0.5)
  sim.set_positions(x);
  ASSERT_FALSE(no_inversion(sim.assembler(), sim.positions())) << "the start must have inverted elements";
  int recovered_at = -1;
  for (int k = 0; k < 120 && recovered_at < 0; ++k) {
    const StepReport r = sim.step();
    ASSERT_TRUE(r.ok) << "step " << k << ": " << r.message;
    if (no_inversion(sim.assembler(), sim.positions())) recovered_at = k;
  }
  EXPECT_GE(recovered_at, 0) << "still inverted after 2 s";
  std::printf("inverted start: no inverted element after step %d\n", recovered_at);
}

// A cube thrown at the floor at 20 m/s (implicit Euler, dt = 1/60, Stable
// Neo-Hookean): it is stopped by the penalty floor without NaN or inversion, and
// penetrates less than 10 % of its size (the penalty's |f| / k).
TEST(StressTests, ExtremeCompressionAgainstTheFloor) {
  const Mesh m = box_mesh(BoxSpec{{0, 0, 0.1}, {1, 1, 1.1}, {2, 2, 2}}, CellType::Tetrahedron, 2);
  const auto mat = make_material("stable-neohookean", LameParameters::from_young_poisson(1e5, 0.45));
  DynamicsOptions o;
  o.dt = 1.0 / 60.0;
  o.density = 1000.0;
  o.gravity = Eigen::Vector3d(0, 0, -9.81);
  o.floor = Floor{Eigen::Vector3d::UnitZ(), 0.0, 1e8};
  DynamicElasticity sim(m, *mat, {}, o);
  sim.set_velocity([](const Eigen::Vector3d&) { return Eigen::Vector3d(0, 0, -20.0); });
  double lowest = 1.0;
  for (int k = 0; k < 60; ++k) {
    const StepReport r = sim.step();
    ASSERT_TRUE(r.ok) << "step " << k << ": " << r.message;
    ASSERT_TRUE(sim.positions().allFinite());
    ASSERT_TRUE(no_inversion(sim.assembler(), sim.positions())) << "step " << k;
    lowest = std::min(lowest, sim.positions().reshaped(3, m.num_nodes()).row(2).minCoeff());
  }
  EXPECT_GT(lowest, -0.1);
  EXPECT_GT(sim.stats().contact_node_steps, 0);
  EXPECT_GT(sim.stats().floor_evaluations, 0);  // the implicit floor term is counted too
  std::printf("floor impact: deepest penetration %.3e m, max from stats %.3e\n", -lowest, sim.stats().max_penetration);
}

}  // namespace
}  // namespace hofem
