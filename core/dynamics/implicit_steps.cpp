// The implicit integrators of TimeStepper: backward Euler as the
// minimisation of the incremental potential (thesis eq. 2.25), and the
// semi-implicit Baraff-Witkin step (one Newton iteration of it, linearised).
#include "dynamics/time_stepper.hpp"

#include "parallel/collectives.hpp"

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <limits>

namespace hofem {

namespace {
double since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

constexpr const char* kOutside = "dynamics: an element left the material's domain on some rank";

// values(A) += s values(B) for matrices of one pattern.
void add_scaled(SparseMatrix& A, double s, const SparseMatrix& B) {
  Eigen::Map<Eigen::VectorXd>(A.valuePtr(), A.nonZeros()) += s * Eigen::Map<const Eigen::VectorXd>(B.valuePtr(), B.nonZeros());
}
}  // namespace

// Over the increment z = y - y_n of the free positions (prescribed DOFs already
// at t + h):
//   E(z) = 1/(2h^2) |z - h v_n|_M^2 + Psi(x) - f_g . z + floor(x)
//          + 1/(2h) |z|_D^2 + c . z / h^2,      x = x_n + z on the free DOFs,
// D = alpha M + beta K(x_n) (frozen over the step, so that
// Rayleigh damping is a potential), and c = (M_fp r_p) with r_p the prescribed
// DOFs' deviation from their inertial path (consistent mass only: the coupling
// of free DOFs to the boundary's acceleration). Its minimiser is the backward
// Euler step: M (z - h v_n)/h^2 = f(x) - D z / h. The unknown is the increment,
// not the position, so that the inertial term's rounding is eps |z| M / h^2
// rather than eps |x| M / h^2 (positions are O(1), increments O(h |v|)); with
// positions Newton stalled at |g| ~ 1e-11 on slowly moving bodies.
class TimeStepper::IncrementalPotential final : public NonlinearProblem {
 public:
  IncrementalPotential(ElasticBody& body, double h, Eigen::VectorXd x_new, const Eigen::VectorXd& y_n,
                       const Eigen::VectorXd& z_tilde, Eigen::VectorXd coupling, const SparseMatrix* K_n)
      : s_(body), h_(h), x_(std::move(x_new)), y_n_(y_n), z_tilde_(z_tilde), c_(std::move(coupling)), K_n_(K_n) {
    inertia_ = 1.0 / (h * h) + s_.options().rayleigh_alpha / h;
  }
  int size() const override { return s_.dofs().num_free(); }

  // Distributed: every term below is this rank's share (its elements,
  // its owned nodes' floor terms), so one sum over ranks gives the energy and one
  // halo sum the gradient.
  double energy(const Eigen::VectorXd& y) override {
    set(y);
    const auto t0 = std::chrono::steady_clock::now();
    const double psi = s_.disc().assembler().energy(s_.material(), x_);
    s_.counters().assembly_seconds += since(t0);
    ++s_.counters().energy_evaluations;
    const double e = s_.disc().sum(std::isfinite(psi) ? psi + quadratic(y) + floor_energy()
                                                          : std::numeric_limits<double>::infinity());
    return std::isfinite(e) ? e : std::numeric_limits<double>::infinity();
  }
  double gradient(const Eigen::VectorXd& y, Eigen::VectorXd& g) override {
    double psi = 0.0;
    assemble(y, s_.counters().gradient_evaluations, g,
             [&](Eigen::VectorXd& g_all) { psi = s_.disc().assembler().gradient(s_.material(), x_, g_all); });
    return s_.disc().sum(psi + quadratic(y) + floor_energy());
  }
  void hessian(const Eigen::VectorXd& y, Eigen::VectorXd& g, SparseMatrix& K, bool project) override {
    assemble(y, s_.counters().hessian_assemblies, g,
             [&](Eigen::VectorXd& g_all) { s_.disc().assembler().hessian(s_.material(), x_, g_all, K, project); });
    // Distributed: K is this rank's share (its elements' mass and stiffness, its
    // owned nodes' floor blocks); hypre sums the shares.
    if (s_.options().floor) s_.options().floor->add_hessian(x_, s_.dofs(), K, s_.disc().counted_nodes());
    if (!s_.mass().lumped()) {
      s_.mass().add_free_to(K, inertia_);
    } else {
      const Eigen::VectorXd m = s_.dofs().restrict(s_.mass().diagonal());
      for (Eigen::Index i = 0; i < m.size(); ++i) K.coeffRef(i, i) += inertia_ * m[i];
    }
    if (K_n_) add_scaled(K, s_.options().rayleigh_beta / h_, *K_n_);
  }
  // Representative force: gravity, the inertial force M v_n / h, the first
  // residual, or the elastic force of a unit strain over the body ((2 mu +
  // lambda) L^2, so that rtol reads as a strain), whichever is largest (the
  // Longva et al. 2020 §6 stop at 1e-5 M a_rep with gravity). The elastic term keeps the
  // tolerance above the rounding of internal forces computed from positions
  // (~eps (2 mu + lambda) |x| h_e per node) when the body comes to rest.
  double force_scale(const Eigen::VectorXd& g0) const override {
    const double h = h_;
    Eigen::VectorXd inertial = mass_free(z_tilde_), gravity = s_.dofs().restrict(s_.gravity_load());
    s_.disc().complete_free(inertial);  // shares -> whole forces before their norms
    s_.disc().complete_free(gravity);
    return std::max({norm(g0), norm(gravity), norm(inertial) / (h * h), s_.elastic_force_scale()});
  }
  double dot(const Eigen::VectorXd& a, const Eigen::VectorXd& b) const override {
    return s_.disc().dot_free(a, b);
  }

 private:
  // `assemble_elastic` (the elastic gradient, with or without the Hessian) at
  // y on every rank together, timed and counted; then the whole gradient over
  // the free DOFs, completed over ranks.
  template <class F>
  void assemble(const Eigen::VectorXd& y, int& counter, Eigen::VectorXd& g, F&& assemble_elastic) {
    set(y);
    const auto t0 = std::chrono::steady_clock::now();
    Eigen::VectorXd g_all;
    s_.disc().on_all_ranks_or_throw<MaterialDomainError>(kOutside, [&] { assemble_elastic(g_all); });
    s_.counters().assembly_seconds += since(t0);
    ++counter;
    g = s_.dofs().restrict(g_all - s_.gravity_load() - floor_forces()) + quadratic_gradient(y);
    s_.disc().complete_free(g);
  }
  void set(const Eigen::VectorXd& z) {
    for (int k = 0; k < z.size(); ++k) x_[s_.dofs().free_dofs()[k]] = y_n_[k] + z[k];
  }
  Eigen::VectorXd mass_free(const Eigen::VectorXd& w) const {
    if (!s_.mass().lumped()) return s_.mass().free_times(w);
    return s_.dofs().restrict(s_.mass().diagonal()).cwiseProduct(w);
  }
  double quadratic(const Eigen::VectorXd& y) const {
    const double h = h_;
    const Eigen::VectorXd d = y - z_tilde_;
    double q = 0.5 / (h * h) * d.dot(mass_free(d)) - s_.dofs().restrict(s_.gravity_load()).dot(y) + c_.dot(y) / (h * h);
    if (s_.options().rayleigh_alpha > 0.0) q += 0.5 * s_.options().rayleigh_alpha / h * y.dot(mass_free(y));
    if (K_n_) q += 0.5 * s_.options().rayleigh_beta / h * y.dot(*K_n_ * y);
    return q;
  }
  // Gradient of quadratic() without its gravity term (added with the forces).
  Eigen::VectorXd quadratic_gradient(const Eigen::VectorXd& y) const {
    const double h = h_;
    Eigen::VectorXd g = mass_free(y - z_tilde_) / (h * h) + c_ / (h * h);
    if (s_.options().rayleigh_alpha > 0.0) g += s_.options().rayleigh_alpha / h * mass_free(y);
    if (K_n_) g += s_.options().rayleigh_beta / h * (*K_n_ * y);
    return g;
  }
  // Each pass over the nodes for the floor term counts as one floor evaluation.
  double floor_energy() const {
    if (!s_.options().floor) return 0.0;
    ++s_.counters().floor_evaluations;
    return s_.options().floor->energy(x_, s_.disc().counted_nodes());
  }
  Eigen::VectorXd floor_forces() const {
    Eigen::VectorXd f = Eigen::VectorXd::Zero(x_.size());
    if (s_.options().floor) {
      ++s_.counters().floor_evaluations;
      s_.options().floor->add_forces(x_, f, s_.disc().counted_nodes());
    }
    return f;
  }

  ElasticBody& s_;
  double h_;
  Eigen::VectorXd x_;
  const Eigen::VectorXd& y_n_;
  const Eigen::VectorXd& z_tilde_;
  Eigen::VectorXd c_;
  const SparseMatrix* K_n_;
  double inertia_ = 0.0;
};

void TimeStepper::step_implicit_euler(StepReport& report, double h) {
  ensure_linear_solver();
  DynamicsStats& stats = body_.counters();
  const DofMap& dofs = body_.dofs();
  const MassModel& mass = body_.mass();
  const Eigen::VectorXd y_n = dofs.restrict(x_), z_tilde = h * dofs.restrict(v_);
  Eigen::VectorXd x_new = x_, v_new = v_;
  body_.impose_motion(t_ + h, x_new, &v_new);
  Eigen::VectorXd coupling = Eigen::VectorXd::Zero(y_n.size());
  if (body_.moving_boundary() && !mass.lumped()) {
    Eigen::VectorXd r_p = Eigen::VectorXd::Zero(x_.size());
    for (int i : dofs.constrained_dofs()) r_p[i] = x_new[i] - (x_[i] + h * v_[i]);
    coupling = dofs.restrict(mass.consistent_times(r_p));
  }
  SparseMatrix K_n;
  if (options_.rayleigh_beta > 0.0) {  // D's stiffness part, frozen at the step's start
    K_n = body_.disc().assembler().new_matrix();
    Eigen::VectorXd g;
    body_.disc().assembler().hessian(body_.material(), x_, g, K_n, true);
    ++stats.hessian_assemblies;
  }
  IncrementalPotential problem(body_, h, x_new, y_n, z_tilde, coupling, K_n.size() > 0 ? &K_n : nullptr);
  // Start from the inertial prediction unless it is outside the material's
  // domain (an inverted element): then from the last state, which is inside.
  Eigen::VectorXd z = z_tilde;
  if (!std::isfinite(problem.energy(z))) z.setZero();
  const int analyses0 = solver_->analyses(), factorizations0 = solver_->factorizations(),
            reuses0 = solver_->setup_reuses();
  const double setup0 = solver_->setup_seconds();
  const auto t0 = std::chrono::steady_clock::now();
  const double assembly0 = stats.assembly_seconds;
  const NewtonResult r = newton_minimize(problem, z, *solver_, options_.newton);
  stats.solve_seconds += since(t0) - (stats.assembly_seconds - assembly0);
  stats.symbolic_analyses += solver_->analyses() - analyses0;
  stats.factorizations += solver_->factorizations() - factorizations0;
  stats.setup_reuses += solver_->setup_reuses() - reuses0;
  stats.setup_seconds += solver_->setup_seconds() - setup0;
  report.setups = solver_->factorizations() - factorizations0;
  report.setup_reuses = solver_->setup_reuses() - reuses0;
  stats.newton_iterations += r.iterations;
  stats.linear_iterations += r.linear_iterations;
  for (const NewtonIteration& it : r.history) {
    report.projected_directions += it.projected;
    stats.projected_directions += it.direction == "projected";
    stats.shifted_directions += it.direction == "shifted";
    stats.gradient_directions += it.direction == "gradient";
  }
  report.newton_iterations = r.iterations;
  report.linear_iterations = r.linear_iterations;
  report.newton_residual = r.final_residual;
  if (!r.converged) {
    report.ok = false;
    report.message = fmt::format("t = {:.6g}: implicit Euler step did not converge: {}", t_ + h, r.message);
    return;
  }
  for (int k = 0; k < z.size(); ++k) {
    const int i = dofs.free_dofs()[k];
    v_new[i] = z[k] / h;
    x_new[i] = y_n[k] + z[k];
  }
  x_ = std::move(x_new);
  v_ = std::move(v_new);
}

// Baraff & Witkin (1998) eq. 6 with D = alpha M + beta K:
//   (M + h D + h^2 K) dv = h (f(x_n) - h K v_n),
// K and f evaluated with the prescribed DOFs already at t + h, so the boundary's
// motion enters through the forces. K is PSD-projected per quadrature point so
// the system stays SPD under compression (as in the thesis' semi-implicit scheme).
void TimeStepper::step_semi_implicit(StepReport& report) {
  ensure_linear_solver();
  DynamicsStats& stats = body_.counters();
  const DofMap& dofs = body_.dofs();
  const MassModel& mass = body_.mass();
  const double h = options_.dt, alpha = options_.rayleigh_alpha, beta = options_.rayleigh_beta;
  Eigen::VectorXd x_new = x_, v_new = v_;
  body_.impose_motion(t_ + h, x_new, &v_new);
  auto t0 = std::chrono::steady_clock::now();
  Eigen::VectorXd g;
  body_.disc().assembler().hessian(body_.material(), x_new, g, K_, true);
  ++stats.hessian_assemblies;
  Eigen::VectorXd f = body_.gravity_load() - g;
  if (options_.floor) {
    ++stats.floor_evaluations;
    options_.floor->add_forces(x_new, f);
    options_.floor->add_hessian(x_new, dofs, K_);
  }
  stats.assembly_seconds += since(t0);
  const Eigen::VectorXd vf = dofs.restrict(v_);
  Eigen::VectorXd Mv, Mfree_diag;
  if (!mass.lumped()) {
    Mv = mass.free_times(vf);
    if (body_.moving_boundary()) f -= mass.consistent_times(body_.prescribed_accelerations(t_ + h));
  } else {
    Mfree_diag = dofs.restrict(mass.diagonal());
    Mv = Mfree_diag.cwiseProduct(vf);
  }
  const Eigen::VectorXd Kv = K_ * vf;
  const Eigen::VectorXd rhs = h * (dofs.restrict(f) - alpha * Mv - beta * Kv - h * Kv);
  // A = (1 + h alpha) M + (h beta + h^2) K, in K's storage.
  Eigen::Map<Eigen::VectorXd>(K_.valuePtr(), K_.nonZeros()) *= h * beta + h * h;
  if (!mass.lumped()) {
    mass.add_free_to(K_, 1.0 + h * alpha);
  } else {
    for (Eigen::Index i = 0; i < Mfree_diag.size(); ++i) K_.coeffRef(i, i) += (1.0 + h * alpha) * Mfree_diag[i];
  }
  t0 = std::chrono::steady_clock::now();
  const int analyses0 = solver_->analyses(), factorizations0 = solver_->factorizations(),
            reuses0 = solver_->setup_reuses();
  const double setup0 = solver_->setup_seconds();
  const bool ok = solver_->factorize(K_);
  Eigen::VectorXd dv;
  if (ok) solver_->solve(rhs, dv);
  stats.solve_seconds += since(t0);
  stats.symbolic_analyses += solver_->analyses() - analyses0;
  stats.factorizations += solver_->factorizations() - factorizations0;
  stats.setup_reuses += solver_->setup_reuses() - reuses0;
  stats.setup_seconds += solver_->setup_seconds() - setup0;
  report.setups = solver_->factorizations() - factorizations0;
  report.setup_reuses = solver_->setup_reuses() - reuses0;
  stats.linear_iterations += solver_->last_iterations();
  report.linear_iterations = solver_->last_iterations();
  if (!ok) {
    report.ok = false;
    report.message = fmt::format("t = {:.6g}: semi-implicit system not positive definite ({})", t_ + h,
                                 solver_->last_error());
    return;
  }
  for (int k = 0; k < dv.size(); ++k) {
    const int i = dofs.free_dofs()[k];
    v_new[i] = v_[i] + dv[k];
    x_new[i] = x_[i] + h * v_new[i];
  }
  x_ = std::move(x_new);
  v_ = std::move(v_new);
}

}  // namespace hofem
