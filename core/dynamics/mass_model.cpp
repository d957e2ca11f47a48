#include "dynamics/mass_model.hpp"

#include <fmt/format.h>

#include <stdexcept>

namespace hofem {

MassModel::MassModel(const Discretization& disc, double density, MassKind kind, MassLumping lumping, int degree,
                     int quadrature_degree, bool factorize)
    : disc_(disc), density_(density), kind_(kind), lumping_(lumping), degree_(degree),
      quadrature_degree_(quadrature_degree) {
  if (kind_ == MassKind::Lumped) {
    lumped_ = disc.assembler().lumped_mass(density, degree, lumping);
    // Over the free DOFs: unsupported finite-cell nodes (constrained) have none.
    Eigen::VectorXd whole = lumped_;  // distributed: this rank's elements' share, completed here
    disc.complete_nodal(whole);
    const Eigen::VectorXd nodal = disc.dofs().restrict(whole);
    const double min_mass = disc.min(nodal.size() > 0 ? nodal.minCoeff() : 1.0);
    if (min_mass <= 0.0)
      throw std::invalid_argument(fmt::format(
          "dynamics: {} lumping gives a non-positive nodal mass ({:.3e}) for order {}; use HRZ lumping or the "
          "consistent mass",
          lumping == MassLumping::RowSum ? "row-sum" : "HRZ", min_mass, disc.mesh().order));
    return;
  }
  if (factorize) solver_ = make_linear_solver("cholmod");
  build_free();
}

std::string MassModel::name() const {
  if (!lumped()) return "consistent";
  return lumping_ == MassLumping::RowSum ? "lumped (row-sum)" : "lumped (HRZ)";
}

void MassModel::build_free() {
  M_ = disc_.assembler().mass_matrix(density_, degree_);
  ++matrices_built_;
  if (!solver_) return;
  if (!solver_->factorize(M_)) throw std::runtime_error("dynamics: the consistent mass is not positive definite");
  ++factorizations_;
}

void MassModel::rebuild() {
  if (!lumped()) build_free();
}

Eigen::VectorXd MassModel::times(const Eigen::VectorXd& r) const {
  return lumped() ? Eigen::VectorXd(lumped_.cwiseProduct(r)) : consistent_times(r);
}

// The consistent mass over ALL DOFs (prescribed ones too: kinetic energy and the
// coupling to prescribed accelerations), assembled once on first use: integrating
// it again per product cost half of an embedded scene's run, whose cut cells carry
// mass rules of 1e5-1e6 points.
Eigen::VectorXd MassModel::consistent_times(const Eigen::VectorXd& r) const {
  if (M_all_.size() == 0) {
    const DofMap all(disc_.mesh().num_nodes(), {});
    Assembler a(disc_.mesh(), all, quadrature_degree_);
    a.set_element_rules(disc_.rules());
    M_all_ = a.mass_matrix(density_, degree_);
    ++matrices_built_;
  }
  return M_all_ * r;
}

}  // namespace hofem
