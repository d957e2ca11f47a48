#include "dynamics/elastic_body.hpp"
#include "basis/quadrature_degrees.hpp"

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <stdexcept>
#include <utility>

namespace hofem {

namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// The prescribed nodes, each checked against a mesh of num_nodes nodes and in
// one motion only (node_set_union). The Discretization adds the finite cells'
// unsupported nodes, held at rest.
std::vector<int> constrained_nodes(const std::vector<PrescribedMotion>& motions, int num_nodes) {
  std::vector<std::vector<int>> sets;
  for (const PrescribedMotion& m : motions) sets.push_back(m.nodes);
  return node_set_union(sets, num_nodes, "prescribed motion", true);
}

void validate(const DynamicsOptions& o) {
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
  }
}

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

ElasticBody::ElasticBody(const Mesh& mesh, const Material& material, std::vector<PrescribedMotion> motions,
                         DynamicsOptions options)
    : disc_(discretization_of(mesh, options)),
      material_(material),
      motions_(on_piece(std::move(motions), mesh, *disc_)),
      options_(std::move(options)) {
  disc_->constrain(constrained_nodes(motions_, disc_->mesh().num_nodes()));
  released_.assign(motions_.size(), 0);
  const DynamicsOptions& o = options_;
  validate(o);
  if (o.floor) options_.floor->normal.normalize();
  const bool explicit_scheme = is_explicit(o.integrator);
  // Consistent mass: N_i N_j (basis/quadrature_degrees.hpp).
  mass_ = std::make_unique<MassModel>(
      *disc_, o.density, o.mass.value_or(explicit_scheme ? MassKind::Lumped : MassKind::Consistent),
      o.lumping.value_or(mesh.order == 1 ? MassLumping::RowSum : MassLumping::HRZ),
      default_quadrature_degrees(mesh.cell, mesh.order).mass,
      o.quadrature_degree, explicit_scheme);
  stats_.mass = mass_->name();
  // Distributed: this rank's elements' share (a partial sum, as every force
  // vector here before complete_free()).
  f_gravity_ = Eigen::VectorXd::Zero(3 * disc_->mesh().num_nodes());
  if (o.gravity.squaredNorm() > 0.0) {
    const Eigen::Vector3d rho_g = o.density * o.gravity;
    f_gravity_ = disc_->assembler().body_force_vector([&](const Eigen::Vector3d&) { return rho_g; }, mass_->degree());
  }
  const double extent = (mesh.nodes.rowwise().maxCoeff() - mesh.nodes.rowwise().minCoeff()).norm();  // the whole body
  elastic_force_scale_ = (2.0 * material.lame().mu + material.lame().lambda) * extent * extent;
  for (const PrescribedMotion& m : motions_) moving_boundary_ = moving_boundary_ || m.moves();
}

Eigen::Map<const Eigen::VectorXd> ElasticBody::reference() const {
  return {mesh().nodes.data(), 3 * mesh().num_nodes()};
}

const DynamicsStats& ElasticBody::stats() const {
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

void ElasticBody::impose_motion(double t, Eigen::VectorXd& x, Eigen::VectorXd* v) const {
  for (const PrescribedMotion& m : motions_)
    for (int n : m.nodes) {
      const Eigen::Vector3d X = mesh().nodes.col(n);
      x.segment<3>(3 * n) = m.position ? m.position(X, t) : X;
      if (v) v->segment<3>(3 * n) = m.velocity ? m.velocity(X, t) : Eigen::Vector3d::Zero();
    }
}

Eigen::VectorXd ElasticBody::prescribed_accelerations(double t) const {
  Eigen::VectorXd a_p = Eigen::VectorXd::Zero(3 * mesh().num_nodes());
  for (const PrescribedMotion& m : motions_)
    if (m.acceleration)
      for (int n : m.nodes) a_p.segment<3>(3 * n) = m.acceleration(mesh().nodes.col(n), t);
  return a_p;
}

Eigen::VectorXd ElasticBody::internal_forces(const Eigen::VectorXd& x) {
  const auto t0 = Clock::now();
  Eigen::VectorXd g;
  disc_->assembler().gradient(material_, x, g);
  ++stats_.gradient_evaluations;
  stats_.assembly_seconds += since(t0);
  return -g;
}

// Step eps |x| / |w| (relative truncation ~eps^2, rounding ~1e-16 / eps).
Eigen::VectorXd ElasticBody::stiffness_times(const Eigen::VectorXd& x, const Eigen::VectorXd& w) {
  const double wn = w.cwiseAbs().maxCoeff();
  if (wn == 0.0) return Eigen::VectorXd::Zero(x.size());
  const double eps = 1e-6 * (x.cwiseAbs().maxCoeff() + 1e-300) / wn;
  return (internal_forces(x - eps * w) - internal_forces(x + eps * w)) / (2.0 * eps);
}

Eigen::VectorXd ElasticBody::forces(const Eigen::VectorXd& x, const Eigen::VectorXd& v) {
  Eigen::VectorXd f = internal_forces(x) + f_gravity_;
  if (options_.floor) {
    ++stats_.floor_evaluations;
    options_.floor->add_forces(x, f);
  }
  if (options_.rayleigh_alpha > 0.0) f -= options_.rayleigh_alpha * mass_->times(v);
  if (options_.rayleigh_beta > 0.0) f -= options_.rayleigh_beta * stiffness_times(x, v);
  return f;
}

Eigen::VectorXd ElasticBody::accelerations(double t, const Eigen::VectorXd& x, const Eigen::VectorXd& v) {
  Eigen::VectorXd f = forces(x, v);
  const Eigen::VectorXd a_p = prescribed_accelerations(t);
  Eigen::VectorXd a = a_p;
  if (mass_->lumped()) {
    for (int i : dofs().free_dofs()) a[i] = f[i] / mass_->diagonal()[i];
  } else {
    if (moving_boundary_) f -= mass_->consistent_times(a_p);
    const auto t0 = Clock::now();
    Eigen::VectorXd af;
    mass_->solve_free(dofs().restrict(f), af);
    stats_.solve_seconds += since(t0);
    dofs().add_free(af, a);
  }
  return a;
}

double ElasticBody::elastic_energy(const Eigen::VectorXd& x) {
  const auto t0 = Clock::now();
  const double e = disc_->sum(disc_->assembler().energy(material_, x));
  stats_.assembly_seconds += since(t0);
  ++stats_.energy_evaluations;
  return e;
}

double ElasticBody::rest_energy() {
  if (!rest_energy_) rest_energy_ = elastic_energy(reference());
  return *rest_energy_;
}

// A released node set becomes free: a new DOF map, and with it a new assembler
// (sparsity pattern) and consistent mass. Happens once per set.
bool ElasticBody::release_due_motions(double t) {
  // Decided by time, so every rank releases the same sets at the same step and
  // asks together whether any rank has nodes of them: the rebuild is collective.
  bool any = false;
  for (size_t k = 0; k < motions_.size(); ++k)
    if (!released_[k] && t >= motions_[k].release - 1e-9 * options_.dt) {
      released_[k] = 1;
      any = disc_->any(!motions_[k].nodes.empty()) || any;  // collective: every rank releases k now
      motions_[k].nodes.clear();
    }
  if (!any) return false;
  ++stats_.releases;
  disc_->constrain(constrained_nodes(motions_, mesh().num_nodes()));  // a new DOF map and pattern
  moving_boundary_ = false;
  for (const PrescribedMotion& m : motions_) moving_boundary_ = moving_boundary_ || (m.moves() && !m.nodes.empty());
  mass_->rebuild();
  return true;
}

}  // namespace hofem
