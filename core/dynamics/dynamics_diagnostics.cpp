#include "dynamics/dynamics_diagnostics.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>

namespace hofem {

Energies energies(ElasticBody& body, const Eigen::VectorXd& x, const Eigen::VectorXd& v) {
  const Discretization& disc = body.disc();
  Energies e;
  e.kinetic = 0.5 * v.dot(body.mass().times(v));
  const double rest = body.rest_energy();
  e.elastic = body.elastic_energy(x) - rest;
  const Eigen::VectorXd u = x - body.reference();
  e.gravity = -body.gravity_load().dot(u);
  if (body.options().floor) e.floor = body.options().floor->energy(x, disc.counted_nodes());
  Eigen::Vector3d parts(e.kinetic, e.gravity, e.floor);
  disc.sum(parts);  // this rank's shares
  e.kinetic = parts[0], e.gravity = parts[1], e.floor = parts[2];
  return e;
}

double kinetic_energy(const ElasticBody& body, const Eigen::VectorXd& v) {
  return body.disc().sum(0.5 * v.dot(body.mass().times(v)));
}

Eigen::Vector3d linear_momentum(const ElasticBody& body, const Eigen::VectorXd& v) {
  const Eigen::VectorXd p = body.mass().times(v);
  Eigen::Vector3d P = Eigen::Vector3d::Zero();
  for (int i = 0; i < body.mesh().num_nodes(); ++i) P += p.segment<3>(3 * i);
  body.disc().sum(P);  // shares of M v
  return P;
}

Eigen::Vector3d angular_momentum(const ElasticBody& body, const Eigen::VectorXd& x, const Eigen::VectorXd& v) {
  const Eigen::VectorXd p = body.mass().times(v);
  Eigen::Vector3d L = Eigen::Vector3d::Zero();
  for (int i = 0; i < body.mesh().num_nodes(); ++i) L += x.segment<3>(3 * i).cross(p.segment<3>(3 * i));
  body.disc().sum(L);
  return L;
}

double estimate_stable_dt(ElasticBody& body, const Eigen::VectorXd& x, int iterations) {
  const double limit = stability_limit(body.options().integrator);
  if (std::isinf(limit)) return std::numeric_limits<double>::infinity();
  const DofMap& dofs = body.dofs();
  const MassModel& mass = body.mass();
  // Power iteration on M^-1 K over the free DOFs (prescribed entries zero).
  Eigen::VectorXd w = Eigen::VectorXd::Zero(x.size());
  for (int i : dofs.free_dofs()) w[i] = std::sin(0.37 * i) + 0.1;
  double lambda = 0.0;
  for (int k = 0; k < iterations; ++k) {
    w /= w.norm();
    Eigen::VectorXd Kw = body.stiffness_times(x, w);
    for (int i : dofs.constrained_dofs()) Kw[i] = 0.0;
    Eigen::VectorXd z = Eigen::VectorXd::Zero(x.size());  // unsupported finite-cell nodes have no mass
    if (mass.lumped()) {
      for (int i : dofs.free_dofs()) z[i] = Kw[i] / mass.diagonal()[i];
    } else {  // explicit integrators with the consistent mass have its factor
      Eigen::VectorXd zf;
      mass.solve_free(dofs.restrict(Kw), zf);
      dofs.add_free(zf, z);
    }
    lambda = w.dot(z) > 0.0 ? z.norm() : lambda;
    w = z;
  }
  // The floor's penalty adds k n n^T per node in contact: by Weyl's inequality
  // lambda_max grows by at most k / (smallest nodal mass) for a lumped mass (for
  // the consistent one, with its smallest diagonal entry, an estimate only).
  if (body.options().floor) lambda += body.options().floor->stiffness / mass.min_diagonal();
  const double omega = std::sqrt(std::max(lambda, 0.0));
  return omega > 0.0 ? limit / omega : std::numeric_limits<double>::infinity();
}

}  // namespace hofem
