#pragma once
// What a run reports about a body's state without advancing it: energies,
// momenta and the explicit integrators' stable time step. Distributed: each
// rank adds its share (its elements' mass products, its owned nodes' floor
// terms) and the sums over ranks are the body's.
#include "dynamics/elastic_body.hpp"

#include <Eigen/Core>

namespace hofem {

struct Energies {
  double kinetic = 0.0, elastic = 0.0, gravity = 0.0, floor = 0.0;
  double total() const { return kinetic + elastic + gravity + floor; }
};

/// Energies at positions x and velocities v; the elastic one relative to the
/// rest state (materials such as Stable Neo-Hookean have psi(I) != 0).
Energies energies(ElasticBody& body, const Eigen::VectorXd& x, const Eigen::VectorXd& v);
/// 1/2 v . M v with the mass in use.
double kinetic_energy(const ElasticBody& body, const Eigen::VectorXd& v);
/// Linear and angular momentum (about the origin) from the mass in use.
Eigen::Vector3d linear_momentum(const ElasticBody& body, const Eigen::VectorXd& v);
Eigen::Vector3d angular_momentum(const ElasticBody& body, const Eigen::VectorXd& x, const Eigen::VectorXd& v);
/// Largest stable dt of the body's integrator at positions x: stability_limit /
/// omega_max, omega_max^2 the largest eigenvalue of M^-1 K by power iteration
/// with Hessian-vector products from differences of internal forces (no
/// Hessian is assembled). Infinity for the implicit integrators.
double estimate_stable_dt(ElasticBody& body, const Eigen::VectorXd& x, int iterations = 40);

}  // namespace hofem
