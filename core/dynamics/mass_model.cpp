#include "dynamics/mass_model.hpp"
#include "solver/solver_factory.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <limits>
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
  Ms_ = disc.assembler().nodal_mass_matrix(density, degree);
  ++matrices_built_;
  if (factorize) {
    SolverSpec direct;  // the consistent mass is SPD and factorised once: CHOLMOD
    direct.method = SolverMethod::Cholmod;
    solver_ = make_linear_solver(direct);
    factorize_free();
  }
}

std::string MassModel::name() const {
  if (!lumped()) return "consistent";
  return lumping_ == MassLumping::RowSum ? "lumped (row-sum)" : "lumped (HRZ)";
}

// The free block in the assembler's DOF pattern, only for the factor (explicit
// integrators with the consistent mass), and dropped once factorised.
void MassModel::factorize_free() {
  SparseMatrix M = disc_.assembler().new_matrix();
  add_free_to(M, 1.0);
  if (!solver_->factorize(M)) throw std::runtime_error("dynamics: the consistent mass is not positive definite");
  ++factorizations_;
}

void MassModel::rebuild() {
  if (solver_) factorize_free();
}

Eigen::VectorXd MassModel::times(const Eigen::VectorXd& r) const {
  return lumped() ? Eigen::VectorXd(lumped_.cwiseProduct(r)) : consistent_times(r);
}

// (Ms (x) I3) r: the DOFs as a 3 x N matrix R (x, y, z of node j in column j),
// R Ms^T = R Ms (Ms is symmetric).
Eigen::VectorXd MassModel::consistent_times(const Eigen::VectorXd& r) const {
  const Eigen::Index n = Ms_.rows();
  if (r.size() != 3 * n) throw std::invalid_argument(fmt::format("mass: vector of {} for {} DOFs", r.size(), 3 * n));
  Eigen::VectorXd y(3 * n);
  Eigen::Map<Eigen::Matrix<double, 3, Eigen::Dynamic>>(y.data(), 3, n).noalias() =
      Eigen::Map<const Eigen::Matrix<double, 3, Eigen::Dynamic>>(r.data(), 3, n) * Ms_;
  return y;
}

Eigen::VectorXd MassModel::free_times(const Eigen::VectorXd& w) const {
  const DofMap& dofs = disc_.dofs();
  Eigen::VectorXd all = Eigen::VectorXd::Zero(dofs.num_dofs());
  dofs.add_free(w, all);
  return dofs.restrict(consistent_times(all));
}

// Column j of K is free DOF j (global DOF free[j], node free[j] / 3); its rows
// ascend in free index and so in global DOF and node. A walk along Ms's column
// of that node picks the entry of each row of the same component.
void MassModel::add_free_to(SparseMatrix& K, double s) const {
  const std::vector<int>& free = disc_.dofs().free_dofs();
  if (K.rows() != static_cast<Eigen::Index>(free.size()) || !K.isCompressed())
    throw std::invalid_argument("mass: add_free_to needs a compressed matrix over the free DOFs");
  const int* ms_start = Ms_.outerIndexPtr();
  const int* ms_row = Ms_.innerIndexPtr();
  const double* ms_value = Ms_.valuePtr();
  const std::int64_t* k_start = K.outerIndexPtr();
  const std::int64_t* k_row = K.innerIndexPtr();
  double* k_value = K.valuePtr();
  const Eigen::Index cols = K.cols();
#pragma omp parallel for schedule(static) if (cols > 30000)
  for (Eigen::Index j = 0; j < cols; ++j) {
    const int node = free[j] / 3, component = free[j] % 3;
    int p = ms_start[node];
    const int end = ms_start[node + 1];
    for (std::int64_t q = k_start[j]; q < k_start[j + 1]; ++q) {
      const int global = free[k_row[q]];
      if (global % 3 != component) continue;
      while (p < end && ms_row[p] < global / 3) ++p;
      if (p < end && ms_row[p] == global / 3) k_value[q] += s * ms_value[p];
    }
  }
}

double MassModel::min_diagonal() const {
  if (lumped()) return lumped_.minCoeff();
  double m = std::numeric_limits<double>::infinity();
  for (int g : disc_.dofs().free_dofs()) m = std::min(m, Ms_.coeff(g / 3, g / 3));
  return m;
}

}  // namespace hofem
