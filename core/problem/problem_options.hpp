#pragma once
// What a static and a dynamic elasticity problem are both given: how their
// elements integrate, which linear solver and Newton settings solve them, and
// whether they run distributed. StaticOptions (problem/) and DynamicsOptions
// (dynamics/) add their own fields to these.
#include "embedded/element_rules.hpp"
#include "solver/newton.hpp"
#include "solver/solver_spec.hpp"

#include <optional>
#include <vector>

namespace hofem {

struct ProblemOptions {
  int quadrature_degree = -1;  ///< stiffness terms; < 0: default for order and material
  /// Finite cell method: per-element stiffness and mass/load rules (finite_cell_quadrature's
  /// element_rules()); nodes they leave without stiffness are held fixed (static) or at rest (dynamic).
  ElementRules element_rules;
  /// Elements given blocks by block preconditioners ("schwarz"): finite cells'
  /// schwarz_block_elements(); unset: every element.
  std::optional<std::vector<int>> preconditioner_blocks;
  /// "auto" (the default, solver/solver_choice.hpp) or a given solver; its
  /// distributed options when `distributed`. The one used is in the report.
  SolverSpec solver;
  /// Distributed over the ranks of MPI_COMM_WORLD: the elements are partitioned
  /// (recursive coordinate bisection) and each rank keeps only its piece of the
  /// mesh (its elements, their owned and ghost nodes): DOF map, pattern, element
  /// data and vectors are the piece's. Energies are summed over the ranks, forces
  /// completed by the node halo, and every linear solve runs on hypre
  /// (solver.distributed). With one rank (no mpirun) it is the same code path.
  /// Every rank must construct and solve the problem (collective calls); node
  /// sets, element rules and loads are given on the global mesh.
  bool distributed = false;
  NewtonOptions newton;
};

}  // namespace hofem
