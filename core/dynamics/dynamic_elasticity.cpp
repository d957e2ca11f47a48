#include "dynamics/dynamic_elasticity.hpp"

#include <stdexcept>
#include <utility>

namespace hofem {

DynamicElasticity::DynamicElasticity(const Mesh& mesh, const Material& material, std::vector<PrescribedMotion> motions,
                                     DynamicsOptions options)
    : body_(std::make_unique<ElasticBody>(mesh, material, std::move(motions), std::move(options))), stepper_(*body_) {}

void DynamicElasticity::set_velocity(const std::function<Eigen::Vector3d(const Eigen::Vector3d&)>& v) {
  Eigen::VectorXd values(velocities().size());
  for (int i = 0; i < mesh().num_nodes(); ++i) values.segment<3>(3 * i) = v(mesh().nodes.col(i));
  set_velocities(values);
}

RankStats DynamicElasticity::rank_stats() const {
  const LinearSolver* solver = stepper_.linear_solver();
  if (!solver)
    throw std::logic_error("DynamicElasticity::rank_stats: not a distributed run that has stepped");
  return body_->disc().rank_stats(*solver);
}

}  // namespace hofem
