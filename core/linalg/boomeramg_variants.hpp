#pragma once
// The BoomerAMG configurations hofem offers, one table (boomeramg_variants.cpp):
// each variant's name - a preconditioner ("cg+amg-nodal") and the distributed
// solver's "amg" key take it -, what it is, and its BoomerAMG parameters.
// Adding a variant is one row there; the preconditioner registry
// (solver/solver_registry.cpp), the scene schema and the help texts read it.
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace hofem {

/// BoomerAMG parameters, each passed to the matching HYPRE_BoomerAMGSet* call
/// (relax_*: SetCycleRelaxType); values as documented in HYPRE_parcsr_ls.h.
struct BoomerAmgOptions {
  int num_functions = 3;          ///< unknowns per node, interleaved (x0 y0 z0 x1 ...)
  int coarsen_type = 10;          ///< 10: HMIS
  int interp_type = 6;            ///< 6: extended+i
  int p_max_elmts = 4;            ///< interpolation truncated to this many entries per row
  double strong_threshold = 0.5;  ///< strength of connection
  int relax_down = 13;            ///< smoother before coarse correction (13: l1 Gauss-Seidel forward)
  int relax_up = 14;              ///< and after (14: the backward sweep, its adjoint)
  int relax_coarse = 9;           ///< 9: Gaussian elimination on the coarsest level
  int num_sweeps = 1;
  int nodal = 0;                  ///< >0: nodal coarsening with this block norm (1: Frobenius, 4: row sum)
  int agg_num_levels = 0;         ///< levels of aggressive coarsening
  int agg_interp_type = 4;        ///< interpolation on those levels (4: multipass)
  int agg_p_max_elmts = 0;
  int num_paths = 1;
  /// >0: rigid-body rotations added to interpolation (InterpVecVariant; needs
  /// nodal coarsening and the node coordinates, i.e. set_mesh_view()).
  int interp_vec_variant = 0;
  int interp_vec_q_max = 4;
};

/// Options of a variant name; throws std::invalid_argument for an unknown one.
BoomerAmgOptions boomeramg_options(std::string_view variant);

struct BoomerAmgVariant {
  std::string_view name;
  std::string_view description;
  BoomerAmgOptions options;
};

/// Every variant, the default ("amg") first.
std::span<const BoomerAmgVariant> boomeramg_variants();
/// Their names, in the table's order.
std::vector<std::string> boomeramg_variant_names();
/// Options of a variant name; throws std::invalid_argument naming the valid ones.
BoomerAmgOptions boomeramg_options(std::string_view variant);

}  // namespace hofem
