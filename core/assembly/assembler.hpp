#pragma once
// Global assembly of a hyperelastic body's energy, gradient and Hessian over
// the free DOFs, plus load vectors and the consistent mass matrix.
//
// Everything that does not change between assemblies is built once in the
// constructor: the quadrature rule and basis tabulation, the sparsity pattern
// with its element-to-nonzero map and element colouring. Each assembly then only
// evaluates elements and writes values. Elements of one colour run in parallel
// (OpenMP), each thread with its own fixed-size workspace: no allocation inside
// the element loop.
#include "assembly/dof_map.hpp"
#include "linalg/sparse_matrix.hpp"
#include "assembly/sparsity_pattern.hpp"
#include "basis/basis_tabulation.hpp"
#include "embedded/element_rules.hpp"
#include "material/material.hpp"
#include "mesh/mesh.hpp"
#include "quadrature/quadrature_rule.hpp"
#include "basis/quadrature_degrees.hpp"

#include <Eigen/Core>

#include <functional>
#include <memory>
#include <vector>

namespace hofem {


/// How a diagonal (lumped) mass is made from the consistent element mass:
/// row sums (order 1, where they are positive) or HRZ (Hinton, Rock &
/// Zienkiewicz 1976: the consistent diagonal scaled to keep each element's mass;
/// positive for every order).
enum class MassLumping { RowSum, HRZ };

/// Nodes of no element that integrates anything (every element around them has
/// empty stiffness and mass rules): they carry no stiffness or mass, so a
/// problem constrains them (finite cells outside the embedded geometry).
std::vector<int> unsupported_nodes(const Mesh& mesh, const ElementRules& rules);

class Assembler {
 public:
  /// quadrature_degree < 0: default_quadrature_degrees(cell, order).stiffness
  /// (basis/quadrature_degrees.hpp: the general rule, curved cells and any material).
  Assembler(const Mesh& mesh, const DofMap& dofs, int quadrature_degree = -1);
  // The assembler keeps references to the mesh and the DOF map: a temporary
  // would dangle, so binding one does not compile.
  Assembler(Mesh&&, const DofMap&, int = -1) = delete;
  Assembler(const Mesh&, DofMap&&, int = -1) = delete;
  Assembler(Mesh&&, DofMap&&, int = -1) = delete;

  const Mesh& mesh() const { return mesh_; }
  const DofMap& dofs() const { return dofs_; }
  const SparsityPattern& pattern() const { return *pattern_; }
  const QuadratureRule& rule() const { return *rule_; }
  int quadrature_degree() const { return degree_; }

  /// x: current positions, 3 * num_nodes (global DOF order). Total elastic energy.
  double energy(const Material& mat, const Eigen::VectorXd& x) const;
  /// Elastic energy of each element (+infinity where the material is not defined).
  Eigen::VectorXd element_energies(const Material& mat, const Eigen::VectorXd& x) const;
  /// Reference volume of each element (the stiffness rule integrates 1 exactly).
  Eigen::VectorXd element_volumes() const;
  /// Per element, the smallest det F (the local volume ratio) over its stiffness
  /// quadrature points at positions x; <= 0 where the element is inverted there.
  /// +inf for an element without points (an empty finite cell).
  Eigen::VectorXd element_min_det_F(const Eigen::VectorXd& x) const;
  /// Elastic energy; g (resized to 3 * num_nodes) receives the internal force vector.
  double gradient(const Material& mat, const Eigen::VectorXd& x, Eigen::VectorXd& g) const;
  /// Energy, internal forces g (all DOFs) and the Hessian K over the free DOFs
  /// (K must have this assembler's pattern; use new_matrix()). project: PSD
  /// projection of dP/dF at every quadrature point.
  double hessian(const Material& mat, const Eigen::VectorXd& x, Eigen::VectorXd& g, SparseMatrix& K, bool project) const;
  /// Per-element quadrature (finite cell method: each cut cell has its own rule,
  /// see embedded/): entry e replaces the stiffness rule of element e for energy,
  /// gradient, Hessian and element volumes; null keeps the standard rule, an
  /// empty rule makes the element contribute nothing. Empty vector: all standard.
  /// Throws std::invalid_argument if the size or an entry's cell/basis does not match.
  void set_element_quadrature(ElementQuadratureList per_element);
  /// The stiffness rules as above and the same for mass matrices, lumped mass,
  /// mass actions and body loads (whose `degree` argument then applies to the
  /// elements with null mass entries only): finite_cell_quadrature's element_rules().
  void set_element_rules(const ElementRules& rules);

  /// A zero matrix with the free-DOF pattern.
  SparseMatrix new_matrix() const { return pattern_->zero_matrix(); }

  /// Consistent load vector sum_e int N_i f(X) dX (all DOFs) of a body force
  /// density f(X), with a rule of the given degree.
  Eigen::VectorXd body_force_vector(const std::function<Eigen::Vector3d(const Eigen::Vector3d&)>& f, int degree) const;
  /// Consistent mass matrix int rho N_i N_j (identity in the components) over the
  /// free DOFs, rule of degree >= 2p for any order.
  SparseMatrix mass_matrix(double density, int degree) const;
  /// The same mass over all nodes as a scalar node matrix Ms (M = Ms (x) I3, with
  /// constrained nodes): 1/9 of mass_matrix()'s entries plus its prescribed
  /// rows, 12 bytes per node pair instead of 48 per DOF pair (dynamics keeps it
  /// for the whole run).
  NodalMatrix nodal_mass_matrix(double density, int degree) const;
  /// Lumped mass per DOF (all 3 * num_nodes DOFs; the three of a node equal).
  Eigen::VectorXd lumped_mass(double density, int degree, MassLumping lumping) const;
  /// M r for the consistent mass over all DOFs, element by element (no matrix):
  /// the coupling of free DOFs to prescribed accelerations.
  Eigen::VectorXd mass_action(double density, int degree, const Eigen::VectorXd& r) const;

 private:
  const Mesh& mesh_;
  const DofMap& dofs_;
  int degree_;
  const QuadratureRule* rule_;
  const BasisTabulation* tab_;
  std::unique_ptr<SparsityPattern> pattern_;
  ElementQuadratureList element_quadrature_;
  ElementQuadratureList mass_quadrature_;
  /// Tabulation and weights element e integrates with.
  const BasisTabulation& tabulation_of(int e) const {
    return element_quadrature_.empty() || !element_quadrature_[e] ? *tab_ : element_quadrature_[e]->tabulation;
  }
  const Eigen::VectorXd& weights_of(int e) const {
    return element_quadrature_.empty() || !element_quadrature_[e] ? rule_->weights : element_quadrature_[e]->rule.weights;
  }
};

}  // namespace hofem
