#include "problem/static_elasticity.hpp"

#include "mesh/mesh_quality.hpp"
#include "parallel/collectives.hpp"
#include "parallel/mpi_runtime.hpp"
#include "basis/quadrature_degrees.hpp"

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace hofem {

namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// The Dirichlet nodes, each checked against a mesh of num_nodes nodes
// (node_set_union). The Discretization adds the finite cells' unsupported ones.
std::vector<int> constrained_nodes(const std::vector<DirichletCondition>& bcs, int num_nodes) {
  std::vector<std::vector<int>> sets;
  for (const DirichletCondition& bc : bcs) sets.push_back(bc.nodes);
  return node_set_union(sets, num_nodes, "static problem: Dirichlet condition", false);
}

}  // namespace

StaticElasticity::StaticElasticity(const Mesh& mesh, const Material& material, std::vector<DirichletCondition> dirichlet,
                                   VectorField body_force, StaticOptions options)
    : material_(material), dirichlet_(std::move(dirichlet)), options_(std::move(options)) {
  const auto t0 = Clock::now();
  // On the given mesh, so that messages name its element indices (and every
  // rank of a distributed run fails alike, none left waiting in a collective).
  validate_mesh(mesh);  // inverted / degenerate elements are rejected with their index
  constrained_nodes(dirichlet_, mesh.num_nodes());  // throws for a node out of range
  const Eigen::VectorXd& external = options_.external_load;
  if (external.size() > 0 && (external.size() != 3 * mesh.num_nodes() || !external.allFinite()))
    throw std::invalid_argument(fmt::format("static problem: external_load needs {} finite entries (got {})",
                                            3 * mesh.num_nodes(), external.size()));
  validate(options_.solver.distributed);
  // From here on a distributed rank sees only its piece of the mesh.
  disc_ = std::make_unique<Discretization>(mesh, options_.distributed, options_.element_rules, options_.quadrature_degree);
  for (auto& bc : dirichlet_) bc.nodes = disc_->local_nodes(bc.nodes);
  finish_setup(constrained_nodes(dirichlet_, disc_->mesh().num_nodes()), disc_->local_nodal(external), body_force);
  setup_seconds_hint_ = seconds_since(t0);
}

StaticElasticity::StaticElasticity(std::unique_ptr<DistributedMesh> piece, const Material& material,
                                   std::vector<DirichletCondition> dirichlet, VectorField body_force,
                                   StaticOptions options)
    : material_(material), dirichlet_(std::move(dirichlet)), options_(std::move(options)) {
  const auto t0 = Clock::now();
  options_.distributed = true;
  validate(options_.solver.distributed);
  if (!options_.element_rules.stiffness.empty() || !options_.element_rules.mass.empty() ||
      options_.external_load.size() > 0)
    throw std::invalid_argument("static problem: element rules and external loads need the global mesh (the other constructor)");
  disc_ = std::make_unique<Discretization>(std::move(piece), options_.quadrature_degree);
  const Mesh& m = disc_->mesh();
  // Each rank checks its own piece; all learn whether any failed (the set-up
  // below is collective), the failing rank with its own message.
  disc_->on_all_ranks_or_throw<MeshError>("static problem: another rank's piece of the mesh is invalid",
                                          [&] { validate_mesh(m); });
  std::vector<int> constrained;
  disc_->on_all_ranks_or_throw<std::invalid_argument>(
      "static problem: a Dirichlet node is out of range on another rank",
      [&] { constrained = constrained_nodes(dirichlet_, m.num_nodes()); });
  finish_setup(constrained, Eigen::VectorXd(), body_force);
  setup_seconds_hint_ = seconds_since(t0);
}

void StaticElasticity::finish_setup(const std::vector<int>& constrained, const Eigen::VectorXd& external,
                                    const VectorField& body_force) {
  Discretization& d = *disc_;
  const Mesh& m = d.mesh();
  d.constrain(constrained);
  solver_choice_ = d.choose_solver(options_.solver);
  solver_ = d.make_solver(solver_choice_.spec, options_.preconditioner_blocks ? &*options_.preconditioner_blocks : nullptr);
  const int load_degree = options_.load_degree >= 0 ? options_.load_degree : default_quadrature_degrees(m.cell, m.order).load;
  f_ext_ = body_force ? d.assembler().body_force_vector(body_force, load_degree) : Eigen::VectorXd::Zero(3 * m.num_nodes());
  d.complete_nodal(f_ext_);  // each rank integrated its own elements
  if (external.size() > 0) f_ext_ += external;
  u_dirichlet_ = Eigen::VectorXd::Zero(3 * m.num_nodes());
  for (const auto& bc : dirichlet_)
    if (bc.displacement)
      for (int n : bc.nodes) u_dirichlet_.segment<3>(3 * n) = bc.displacement(m.nodes.col(n));
  u_full_ = Eigen::VectorXd::Zero(3 * m.num_nodes());
  x_ = Eigen::Map<const Eigen::VectorXd>(m.nodes.data(), 3 * m.num_nodes());
  assembly_seconds_ = 0.0;
}

RankStats StaticElasticity::rank_stats() const { return disc_->rank_stats(*solver_); }

double StaticElasticity::external_work() const {
  // Consistent vectors: owned nodes only, summed over ranks (each DOF once).
  return disc_->dot_nodal(f_ext_, u_full_);
}

void StaticElasticity::set_state(const Eigen::VectorXd& u_free) {
  const DofMap& dofs = disc_->dofs();
  for (int d : dofs.constrained_dofs()) u_full_[d] = load_ * u_dirichlet_[d];
  const auto& free = dofs.free_dofs();
  for (int i = 0; i < dofs.num_free(); ++i) u_full_[free[i]] = u_free[i];
  const Mesh& m = mesh();
  x_ = Eigen::Map<const Eigen::VectorXd>(m.nodes.data(), 3 * m.num_nodes()) + u_full_;
}

double StaticElasticity::energy(const Eigen::VectorXd& u) {
  set_state(u);
  const auto t0 = Clock::now();
  const double e = disc_->sum(disc_->assembler().energy(material_, x_));  // each rank integrated its own elements
  assembly_seconds_ += seconds_since(t0);
  return e - load_ * external_work();
}

double StaticElasticity::gradient(const Eigen::VectorXd& u, Eigen::VectorXd& g) {
  set_state(u);
  const auto t0 = Clock::now();
  double e = std::numeric_limits<double>::infinity();
  try {
    disc_->on_all_ranks_or_throw<MaterialDomainError>(
        "outside the material's domain", [&] { e = disc_->assembler().gradient(material_, x_, g_full_); });
  } catch (const MaterialDomainError&) {
    g.setZero(disc_->dofs().num_free());
    assembly_seconds_ += seconds_since(t0);
    return std::numeric_limits<double>::infinity();
  }
  e = disc_->sum(e);
  disc_->complete_nodal(g_full_);  // partial nodal forces -> full, on owners and ghosts alike
  assembly_seconds_ += seconds_since(t0);
  g = disc_->dofs().restrict(g_full_ - load_ * f_ext_);
  return e - load_ * external_work();
}

void StaticElasticity::hessian(const Eigen::VectorXd& u, Eigen::VectorXd& g, SparseMatrix& K, bool project) {
  set_state(u);
  const auto t0 = Clock::now();
  // Distributed: this rank's share of K (its elements, over its piece); forces completed.
  disc_->on_all_ranks_or_throw<MaterialDomainError>(
      "static problem: an element left the material's domain on some rank",
      [&] { disc_->assembler().hessian(material_, x_, g_full_, K, project); });
  disc_->complete_nodal(g_full_);
  assembly_seconds_ += seconds_since(t0);
  g = disc_->dofs().restrict(g_full_ - load_ * f_ext_);
}

double StaticElasticity::force_scale(const Eigen::VectorXd& g0) const {
  // The largest of: the applied body force, the force the current load step
  // adds (body-force increment plus the reaction to the prescribed boundary
  // increment, measured by the predictor), and the first residual. Relative to
  // this, ||g|| <= rtol * scale does not depend on units or mesh size; a problem
  // loaded only through its boundary (zero body force) still has a scale.
  const double s = std::max({load_ * norm(disc_->dofs().restrict(f_ext_)), step_force_, norm(g0)});
  return s > 0.0 ? s : 1.0;
}

Eigen::VectorXd StaticElasticity::predict(const Eigen::VectorXd& u, double from, double to) {
  Eigen::VectorXd g0, g1, du;
  SparseMatrix& K = K_;  // the pattern-shaped matrix this problem keeps
  load_ = from;
  // u is a converged state (a minimum at `from`, or the undeformed start), where
  // the exact tangent is positive definite: try it first. Projecting every
  // quadrature point's tangent costs as much again as the assembly (Neo-Hookean
  // P3 n = 8: 0.147 vs 0.078 s), so it is the fallback, for a state where the
  // exact tangent does not factorise or breaks CG (a buckled equilibrium).
  hessian(u, g0, K, false);
  bool projected = false;
  if (!solver_->factorize(K)) {
    hessian(u, g0, K, true);
    projected = true;
    if (!solver_->factorize(K)) return u;
  }
  solver_->set_relative_tolerance(options_.newton.linear_rtol);
  // d g / d load by a forward difference: the body-force part is linear in the
  // load, and the Dirichlet part is evaluated on a tiny boundary move (1e-6 of
  // the step) that cannot fold an element.
  const double eps = 1e-6 * (to - from);
  load_ = from + eps;
  if (!std::isfinite(gradient(u, g1))) return u;
  const Eigen::VectorXd dg = (g1 - g0) / eps * (to - from);
  step_force_ = norm(dg);
  try {
    solver_->solve(-dg, du);
  } catch (const std::runtime_error&) {  // an iterative solver that did not converge (or broke down)
    if (projected) return u;  // no prediction
    load_ = from;
    hessian(u, g0, K, true);
    if (!solver_->factorize(K)) return u;
    try {
      solver_->solve(-dg, du);
    } catch (const std::runtime_error&) {
      return u;
    }
  }
  predictor_iterations_ += solver_->last_iterations();
  const Eigen::VectorXd trial = u + du;
  load_ = to;
  return std::isfinite(energy(trial)) ? trial : u;
}

// A quadratic energy (constant tangent): from u, one linear solve K du = -g reaches
// the equilibrium at `to`. The residual after the step is the linear solve's own,
// so asking the solver for rtol * scale / |g| meets Newton's test in this one
// solve (Newton then only confirms it; it takes steps of its own only if an
// iterative solver stopped short). The predictor's finite-difference load
// derivative would leave a ~1e-10 relative error and cost a second solve.
Eigen::VectorXd StaticElasticity::linear_step(const Eigen::VectorXd& u, double to) {
  Eigen::VectorXd g, du;
  load_ = to;
  hessian(u, g, K_, false);  // PSD already: a constant tangent is
  if (!solver_->factorize(K_)) return u;  // Newton reports the failure
  const double g_norm = norm(g);
  if (!(g_norm > 0.0)) return u;
  step_force_ = g_norm;
  solver_->set_relative_tolerance(std::min(options_.newton.linear_rtol, options_.newton.rtol * force_scale(g) / g_norm));
  try {
    solver_->solve(-g, du);
  } catch (const std::runtime_error&) {  // an iterative solver that did not converge: Newton takes over
    return u;
  }
  predictor_iterations_ += solver_->last_iterations();
  return u + du;
}

double residual_over_tolerance(const StaticReport& report, double rtol) {
  return report.steps.empty() ? std::numeric_limits<double>::infinity()
                              : residual_over_tolerance(report.steps.back(), rtol);
}

StaticReport StaticElasticity::solve() {
  StaticReport report;
  report.setup_seconds = setup_seconds_hint_;
  const auto t0 = Clock::now();
  assembly_seconds_ = 0.0;
  Eigen::VectorXd u = Eigen::VectorXd::Zero(disc_->dofs().num_free());
  // Adaptive load stepping: a failed step is retried at half the size (up to
  // max_load_halvings times in a row); after a success the step doubles again.
  double done = 0.0, step = 1.0;
  int failures_in_a_row = 0;
  while (done < 1.0) {
    const double target = std::min(1.0, done + step);
    step_force_ = 0.0;
    Eigen::VectorXd trial = material_.constant_tangent() ? linear_step(u, target)
                            : options_.predictor           ? predict(u, done, target)
                                                           : u;
    load_ = target;
    NewtonResult r = newton_minimize(*this, trial, *solver_, options_.newton);
    report.newton_iterations += r.iterations;
    report.linear_iterations += r.linear_iterations + predictor_iterations_;
    predictor_iterations_ = 0;
    report.steps.push_back(r);
    if (r.converged) {
      u = trial;
      done = load_;
      ++report.load_steps;
      failures_in_a_row = 0;
      step = std::min(2.0 * step, 1.0);
      continue;
    }
    if (++failures_in_a_row > options_.max_load_halvings) {
      report.message = fmt::format("failed at load {:.4f} after {} halvings: {}", load_, options_.max_load_halvings, r.message);
      break;
    }
    step *= 0.5;
  }
  report.converged = done >= 1.0;
  if (report.converged) report.message = fmt::format("converged in {} load step(s), {} Newton iterations", report.load_steps, report.newton_iterations);
  set_state(u);
  report.assembly_seconds = assembly_seconds_;
  report.solve_seconds = std::max(0.0, seconds_since(t0) - assembly_seconds_);
  report.factorizations = solver_->factorizations();
  report.symbolic_analyses = solver_->analyses();
  // The count the scenes report: one Hessian assembly per Newton iteration.
  report.polar_decompositions =
      polar_decompositions(material_, report.newton_iterations, disc_->global_elements(),
                           static_cast<long long>(disc_->assembler().rule().size()));
  report.linear_solver = disc_->solver_name(solver_choice_);
  report.linear_solver_reason = solver_choice_.reason;
  return report;
}

}  // namespace hofem
