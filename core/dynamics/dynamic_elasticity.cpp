#include "dynamics/dynamic_elasticity.hpp"

#include "assembly/distributed_dofs.hpp"
#include "parallel/collectives.hpp"
#include "parallel/mpi_runtime.hpp"

#include <Eigen/Geometry>
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>

namespace hofem {

namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// The prescribed nodes, plus `unsupported` (finite cells: nodes no element
// integrates anything for, held at rest).
// The prescribed nodes, each checked against a mesh of num_nodes nodes and in
// one motion only (node_set_union). The Discretization adds the finite cells'
// unsupported nodes, held at rest.
std::vector<int> constrained_nodes(const std::vector<PrescribedMotion>& motions, int num_nodes) {
  std::vector<std::vector<int>> sets;
  for (const PrescribedMotion& m : motions) sets.push_back(m.nodes);
  return node_set_union(sets, num_nodes, "prescribed motion", true);
}

bool all_finite(const Eigen::VectorXd& v) { return v.allFinite(); }

// The body's discretization; distributed runs keep only this rank's piece of the mesh.
std::unique_ptr<Discretization> discretization_of(const Mesh& mesh, const DynamicsOptions& o) {
  if (o.distributed) {
    if (o.integrator != Integrator::ImplicitEuler || o.rayleigh_beta > 0.0)
      throw std::invalid_argument("dynamics: distributed runs support implicit Euler without stiffness damping (so far)");
    validate(o.solver.distributed);
  }
  return std::make_unique<Discretization>(mesh, o.distributed, o.element_rules, o.quadrature_degree);
}

// Prescribed node sets checked on the given mesh, then renumbered onto mesh() (the piece).
std::vector<PrescribedMotion> on_piece(std::vector<PrescribedMotion> motions, const Mesh& mesh,
                                       const Discretization& disc) {
  constrained_nodes(motions, mesh.num_nodes());  // throws for out-of-range or repeated nodes
  for (PrescribedMotion& m : motions) m.nodes = disc.local_nodes(m.nodes);
  return motions;
}

}  // namespace

DynamicElasticity::DynamicElasticity(const Mesh& mesh, const Material& material, std::vector<PrescribedMotion> motions,
                                     DynamicsOptions options)
    : disc_(discretization_of(mesh, options)),
      mesh_(disc_->mesh()),
      dofs_(disc_->dofs()),
      material_(material),
      motions_(on_piece(std::move(motions), mesh, *disc_)),
      options_(std::move(options)) {
  disc_->constrain(constrained_nodes(motions_, mesh_.num_nodes()));
  released_.assign(motions_.size(), 0);
  const DynamicsOptions& o = options_;
  if (!(o.dt > 0.0) || !std::isfinite(o.dt)) throw std::invalid_argument(fmt::format("dynamics: dt must be > 0 (got {})", o.dt));
  if (!(o.density > 0.0) || !std::isfinite(o.density))
    throw std::invalid_argument(fmt::format("dynamics: density must be > 0 (got {})", o.density));
  if (!(o.rayleigh_alpha >= 0.0) || !(o.rayleigh_beta >= 0.0))
    throw std::invalid_argument("dynamics: Rayleigh damping coefficients must be >= 0");
  if (!o.gravity.allFinite()) throw std::invalid_argument("dynamics: gravity must be finite");
  if (o.floor) {
    if (!(o.floor->stiffness > 0.0) || !std::isfinite(o.floor->stiffness))
      throw std::invalid_argument(fmt::format("dynamics: floor stiffness must be > 0 (got {})", o.floor->stiffness));
    if (!(o.floor->normal.norm() > 0.0)) throw std::invalid_argument("dynamics: floor normal must be non-zero");
    options_.floor->normal.normalize();
  }
  const bool explicit_scheme = is_explicit(o.integrator);
  // Consistent mass: N_i N_j has degree 2p on affine cells (2p per direction on hexes).
  mass_ = std::make_unique<MassModel>(
      *disc_, o.density, o.mass.value_or(explicit_scheme ? MassKind::Lumped : MassKind::Consistent),
      o.lumping.value_or(mesh.order == 1 ? MassLumping::RowSum : MassLumping::HRZ), 2 * mesh.order,
      o.quadrature_degree, explicit_scheme);
  stats_.mass = mass_->name();
  // Distributed: this rank's elements' share (a partial sum, as every force
  // vector here before complete_free()).
  f_gravity_ = Eigen::VectorXd::Zero(3 * mesh_.num_nodes());
  if (o.gravity.squaredNorm() > 0.0) {
    const Eigen::Vector3d rho_g = o.density * o.gravity;
    f_gravity_ = disc_->assembler().body_force_vector([&](const Eigen::Vector3d&) { return rho_g; }, mass_->degree());
  }
  const double extent = (mesh.nodes.rowwise().maxCoeff() - mesh.nodes.rowwise().minCoeff()).norm();  // the whole body
  elastic_force_scale_ = (2.0 * material.lame().mu + material.lame().lambda) * extent * extent;
  x_ = Eigen::Map<const Eigen::VectorXd>(mesh_.nodes.data(), 3 * mesh_.num_nodes());
  v_ = Eigen::VectorXd::Zero(x_.size());
  for (const PrescribedMotion& m : motions_) moving_boundary_ = moving_boundary_ || m.moves();
  impose_motion(0.0, x_, &v_);
}

DynamicElasticity::~DynamicElasticity() = default;

const DynamicsStats& DynamicElasticity::stats() const {
  // Every energy, gradient or Hessian assembly evaluates the material once per
  // quadrature point of every element.
  const long long evaluations = stats_.energy_evaluations + stats_.gradient_evaluations + stats_.hessian_assemblies;
  stats_.mass_matrices_built = mass_->matrices_built();
  stats_.mass_factorizations = mass_->factorizations();
  stats_.polar_decompositions =
      polar_decompositions(material_, evaluations, disc_->global_elements(),
                           static_cast<long long>(disc_->assembler().rule().size()));
  return stats_;
}

RankStats DynamicElasticity::rank_stats() const {
  if (!solver_) throw std::logic_error("DynamicElasticity::rank_stats: not a distributed run that has stepped");
  return disc_->rank_stats(*solver_);
}

void DynamicElasticity::ensure_linear_solver() {
  if (solver_) return;
  const SolverChoice choice = disc_->choose_solver(options_.solver);
  stats_.linear_solver = disc_->solver_name(choice);
  stats_.linear_solver_reason = choice.reason;
  solver_ = disc_->make_solver(choice.spec, options_.preconditioner_blocks ? &*options_.preconditioner_blocks : nullptr);
  K_ = disc_->assembler().new_matrix();
}

void DynamicElasticity::set_velocity(const std::function<Eigen::Vector3d(const Eigen::Vector3d&)>& v) {
  Eigen::VectorXd values(v_.size());
  for (int i = 0; i < mesh_.num_nodes(); ++i) values.segment<3>(3 * i) = v(mesh_.nodes.col(i));
  set_velocities(values);
}

void DynamicElasticity::set_velocities(const Eigen::VectorXd& v) {
  if (v.size() != v_.size() || !v.allFinite())
    throw std::invalid_argument(fmt::format("dynamics: velocities need {} finite entries", v_.size()));
  v_ = v;
  impose_motion(t_, x_, &v_);
  a_valid_ = false;
  energy_reference_ = -1.0;
}

void DynamicElasticity::set_positions(const Eigen::VectorXd& x) {
  if (x.size() != x_.size() || !x.allFinite())
    throw std::invalid_argument(fmt::format("dynamics: positions need {} finite entries", x_.size()));
  x_ = x;
  impose_motion(t_, x_, &v_);
  a_valid_ = false;
  energy_reference_ = -1.0;
}

void DynamicElasticity::impose_motion(double t, Eigen::VectorXd& x, Eigen::VectorXd* v) const {
  for (const PrescribedMotion& m : motions_)
    for (int n : m.nodes) {
      const Eigen::Vector3d X = mesh_.nodes.col(n);
      x.segment<3>(3 * n) = m.position ? m.position(X, t) : X;
      if (v) v->segment<3>(3 * n) = m.velocity ? m.velocity(X, t) : Eigen::Vector3d::Zero();
    }
}

Eigen::VectorXd DynamicElasticity::displacement() const {
  return x_ - Eigen::Map<const Eigen::VectorXd>(mesh_.nodes.data(), 3 * mesh_.num_nodes());
}

double DynamicElasticity::elastic_energy(const Eigen::VectorXd& x) const {
  return disc_->sum(disc_->assembler().energy(material_, x));
}


Energies DynamicElasticity::energies() {
  Energies e;
  // Distributed: the mass products are this rank's elements' share and the
  // floor counts its owned nodes, so each term's sum over ranks is the body's.
  e.kinetic = 0.5 * v_.dot(mass_->times(v_));
  const auto t0 = Clock::now();
  if (!rest_energy_) {
    rest_energy_ = elastic_energy(Eigen::Map<const Eigen::VectorXd>(mesh_.nodes.data(), x_.size()));
    ++stats_.energy_evaluations;
  }
  e.elastic = elastic_energy(x_) - *rest_energy_;
  stats_.assembly_seconds += since(t0);
  ++stats_.energy_evaluations;
  e.gravity = -f_gravity_.dot(displacement());
  if (options_.floor) e.floor = options_.floor->energy(x_, disc_->counted_nodes());
  Eigen::Vector3d parts(e.kinetic, e.gravity, e.floor);
  disc_->sum(parts);  // this rank's shares
  e.kinetic = parts[0], e.gravity = parts[1], e.floor = parts[2];
  return e;
}

Eigen::Vector3d DynamicElasticity::linear_momentum() const {
  const Eigen::VectorXd p = mass_->times(v_);
  Eigen::Vector3d P = Eigen::Vector3d::Zero();
  for (int i = 0; i < mesh_.num_nodes(); ++i) P += p.segment<3>(3 * i);
  disc_->sum(P);  // shares of M v
  return P;
}

Eigen::Vector3d DynamicElasticity::angular_momentum() const {
  const Eigen::VectorXd p = mass_->times(v_);
  Eigen::Vector3d L = Eigen::Vector3d::Zero();
  for (int i = 0; i < mesh_.num_nodes(); ++i) L += x_.segment<3>(3 * i).cross(p.segment<3>(3 * i));
  disc_->sum(L);
  return L;
}

double DynamicElasticity::kinetic_energy() const {
  return disc_->sum(0.5 * v_.dot(mass_->times(v_)));
}

double DynamicElasticity::estimate_stable_dt(int iterations) {
  const double limit = stability_limit(options_.integrator);
  if (std::isinf(limit)) return std::numeric_limits<double>::infinity();
  // Power iteration on M^-1 K over the free DOFs (prescribed entries zero).
  Eigen::VectorXd w = Eigen::VectorXd::Zero(x_.size());
  for (int i : dofs_.free_dofs()) w[i] = std::sin(0.37 * i) + 0.1;
  double lambda = 0.0;
  for (int k = 0; k < iterations; ++k) {
    w /= w.norm();
    Eigen::VectorXd Kw = stiffness_times(x_, w);
    for (int i : dofs_.constrained_dofs()) Kw[i] = 0.0;
    Eigen::VectorXd z;
    if (mass_->lumped()) {
      z = Eigen::VectorXd::Zero(x_.size());  // unsupported finite-cell nodes have no mass
      for (int i : dofs_.free_dofs()) z[i] = Kw[i] / mass_->diagonal()[i];
    } else {  // explicit integrators with the consistent mass have its factor
      Eigen::VectorXd zf;
      mass_->solve_free(dofs_.restrict(Kw), zf);
      z = Eigen::VectorXd::Zero(x_.size());
      dofs_.add_free(zf, z);
    }
    lambda = w.dot(z) > 0.0 ? z.norm() : lambda;
    w = z;
  }
  // The floor's penalty adds k n n^T per node in contact: by Weyl's inequality
  // lambda_max grows by at most k / (smallest nodal mass) for a lumped mass (for
  // the consistent one, with its smallest diagonal entry, an estimate only).
  if (options_.floor) {
    const double m_min = mass_->min_diagonal();
    lambda += options_.floor->stiffness / m_min;
  }
  const double omega = std::sqrt(std::max(lambda, 0.0));
  return omega > 0.0 ? limit / omega : std::numeric_limits<double>::infinity();
}

// Backward Euler with step halving: a step whose Newton solve fails (a
// nonconvex region such as a buckling tube, where the projected Newton
// converges slowly) is redone as two half steps, up to kMaxHalvings deep. The
// state only changes when a (sub)step converges.
void DynamicElasticity::implicit_euler_adaptive(StepReport& report, double h, int depth) {
  constexpr int kMaxHalvings = 4;
  const double saved_dt = options_.dt, t0 = t_;
  options_.dt = h;
  StepReport attempt;
  step_implicit_euler(attempt);
  options_.dt = saved_dt;
  report.newton_iterations += attempt.newton_iterations;
  report.linear_iterations += attempt.linear_iterations;
  report.newton_residual = attempt.newton_residual;
  if (attempt.ok) return;
  if (depth >= kMaxHalvings) {
    report.ok = false;
    report.message = attempt.message + fmt::format(" (after {} halvings of dt)", kMaxHalvings);
    return;
  }
  ++stats_.step_halvings;
  implicit_euler_adaptive(report, 0.5 * h, depth + 1);
  if (!report.ok) return;
  t_ = t0 + 0.5 * h;
  implicit_euler_adaptive(report, 0.5 * h, depth + 1);
  t_ = t0;  // step() advances the time by the whole step
}

// A released node set becomes free: new DOF map, and with it a new assembler
// (sparsity pattern), consistent mass and linear solver. Happens once per set.
void DynamicElasticity::release_due_motions() {
  // Decided by time, so every rank releases the same sets at the same step and
  // asks together whether any rank has nodes of them: the rebuild is collective.
  bool any = false;
  for (size_t k = 0; k < motions_.size(); ++k)
    if (!released_[k] && t_ >= motions_[k].release - 1e-9 * options_.dt) {
      released_[k] = 1;
      any = disc_->any(!motions_[k].nodes.empty()) || any;  // collective: every rank releases k now
      motions_[k].nodes.clear();
    }
  if (!any) return;
  ++stats_.releases;
  disc_->constrain(constrained_nodes(motions_, mesh_.num_nodes()));  // a new DOF map and pattern
  moving_boundary_ = false;
  for (const PrescribedMotion& m : motions_) moving_boundary_ = moving_boundary_ || (m.moves() && !m.nodes.empty());
  mass_->rebuild();
  if (solver_) {
    solver_.reset();  // a new pattern and DOF map: mesh-aware preconditioners start over (and global rows)
    ensure_linear_solver();
  }
  a_valid_ = false;
}

StepReport DynamicElasticity::step() {
  const auto t0 = Clock::now();
  release_due_motions();
  StepReport report;
  const Eigen::VectorXd x_old = x_, v_old = v_;
  const double t_old = t_;
  const bool explicit_scheme = is_explicit(options_.integrator);
  if (explicit_scheme && energy_reference_ < 0.0) {
    // Scale of energies a stable run can reach: the initial kinetic and elastic
    // energy, the work gravity can do over the body's extent (and its height
    // above a floor), and the kinetic energy of the boundary's motion.
    const Eigen::Map<const Eigen::VectorXd> X(mesh_.nodes.data(), x_.size());
    const Eigen::Vector3d lo = mesh_.nodes.rowwise().minCoeff(), hi = mesh_.nodes.rowwise().maxCoeff();
    double extent = (hi - lo).norm() + (x_ - X).cwiseAbs().maxCoeff();
    if (options_.floor) extent += std::abs(options_.floor->depth(lo));
    const double gravity_work = f_gravity_.cwiseAbs().sum() * extent;
    const double elastic = elastic_energy(x_);
    ++stats_.energy_evaluations;
    double boundary = 0.0;
    Eigen::VectorXd vb = Eigen::VectorXd::Zero(x_.size());
    for (int i : dofs_.constrained_dofs()) vb[i] = v_[i];
    boundary = 0.5 * vb.dot(mass_->times(vb));
    energy_reference_ = std::max({kinetic_energy() + elastic, gravity_work, boundary,
                                  std::numeric_limits<double>::min()});
  }
  try {
    switch (options_.integrator) {
      case Integrator::ExplicitEuler: step_explicit_euler(); break;
      case Integrator::SymplecticEuler: step_symplectic_euler(); break;
      case Integrator::Leapfrog: step_leapfrog(); break;
      case Integrator::RK4: step_rk4(); break;
      case Integrator::SemiImplicit: step_semi_implicit(report); break;
      case Integrator::ImplicitEuler: implicit_euler_adaptive(report, options_.dt, 0); break;
    }
  } catch (const MaterialDomainError& e) {
    report.ok = false;
    report.message = fmt::format("t = {:.6g}: {} (an element inverted{})", t_old + options_.dt, e.what(),
                                 explicit_scheme ? "; the explicit step may be unstable at this dt" : "");
  }
  if (report.ok) {
    t_ = t_old + options_.dt;
    bool finite = all_finite(x_) && all_finite(v_);
    finite = !disc_->any(!finite);  // every rank rolls back together
    if (!finite) {
      report.ok = false;
      report.message = fmt::format("t = {:.6g}: non-finite positions or velocities", t_);
    } else if (explicit_scheme) {
      const double kinetic = kinetic_energy();
      if (kinetic > options_.instability_factor * energy_reference_) {
        report.ok = false;
        report.message = fmt::format("t = {:.6g}: kinetic energy {:.3e} > {:.0e} x the run's energy scale {:.3e}",
                                     t_, kinetic, options_.instability_factor, energy_reference_);
      }
    }
  }
  if (!report.ok) {
    x_ = x_old;
    v_ = v_old;
    t_ = t_old;
    a_valid_ = false;
    if (explicit_scheme) {
      double stable = std::numeric_limits<double>::quiet_NaN();
      try {
        stable = estimate_stable_dt();
      } catch (const MaterialDomainError&) {
        // The last good state is too close to inversion for the difference
        // quotients; the message then says so through the NaN.
      }
      const std::string bound = std::isnan(stable) ? std::string("a smaller dt (the last state is too close to "
                                                                 "inversion to estimate omega_max)")
                                                   : fmt::format("dt < {:.3e} here", stable);
      report.message += fmt::format(": unstable; {} at dt = {:.3e} needs {} (omega_max from power "
                                    "iteration on M^-1 K{})",
                                    integrator_name(options_.integrator), options_.dt, bound,
                                    options_.integrator == Integrator::ExplicitEuler
                                        ? "; explicit Euler is unstable at any dt without damping"
                                        : "");
    }
  }
  if (options_.floor && report.ok) {
    const int contacts = disc_->sum(options_.floor->contacts(x_, disc_->counted_nodes()));
    const double depth = disc_->max(options_.floor->max_depth(x_));
    stats_.contact_node_steps += contacts;
    stats_.max_penetration = std::max(stats_.max_penetration, depth);
  }
  report.time = t_;
  report.seconds = since(t0);
  return report;
}

}  // namespace hofem
