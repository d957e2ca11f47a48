#pragma once
// Manufactured solutions on the unit cube [0,1]^3: a displacement u*
// is chosen, the body force that makes it an equilibrium is computed from the
// material law, u = u* is prescribed on the whole boundary, and the discrete
// solution's L2 and H1-seminorm errors are measured.
//
//   u*_x = s sin(pi x) sin(pi y) sin(pi z)
//   u*_y = s 0.5 sin(pi(x+1/4)) sin(pi(y+1/4)) sin(pi(z+1/4))
//   u*_z = s 0.25 cos(pi x) cos(pi y) e^z
// with s = 1 (linear elasticity) or 0.1 (the hyperelastic materials), E = 1, nu = 0.3.
// Body force f = -Div P(F*), F* = I + grad u*, evaluated exactly:
//   f_i = - sum_{j,k,l} dP_ij/dF_kl (F*) d^2 u*_k / dX_l dX_j.
#include "io/vtu_writer.hpp"
#include "material/material.hpp"
#include "mesh/mesh.hpp"
#include "problem/static_elasticity.hpp"
#include "quadrature/cell_type.hpp"

#include <Eigen/Core>

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace hofem {

struct ManufacturedDisplacement {
  double scale = 1.0;
  Eigen::Vector3d value(const Eigen::Vector3d& X) const;
  /// G(i, j) = d u*_i / d X_j
  Eigen::Matrix3d gradient(const Eigen::Vector3d& X) const;
  /// H[k](l, j) = d^2 u*_k / dX_l dX_j
  void hessians(const Eigen::Vector3d& X, Eigen::Matrix3d H[3]) const;
};

/// Body force that puts a displacement field in equilibrium, from the material
/// tangent A = dP/dF at the point and the field's second derivatives H[k](l, j) =
/// d^2 u_k / dX_l dX_j:  f_i = -Div P = -sum_{j,k,l} A(i + 3j, k + 3l) H[k](l, j).
Eigen::Vector3d equilibrium_body_force(const Eigen::Matrix<double, 9, 9>& A, const Eigen::Matrix3d H[3]);

/// The manufactured problems' material parameters (E = 1, nu = 0.3) and the
/// scale of u* for a material: 1 for linear elasticity (one linear solve), 0.1
/// for the hyperelastic materials (F* stays within ~0.5 of I, det F* > 0).
LameParameters mms_lame();
double mms_displacement_scale(const std::string& problem);

/// The body force of a manufactured problem at X (computed elsewhere, e.g. the
/// verification suite's symbolic material law, instead of from core/material).
using MmsBodyForce = std::function<Eigen::Vector3d(const Eigen::Vector3d&)>;

struct MmsCase {
  std::string problem = "linear";  ///< the material: a name of material_names()
  CellType cell = CellType::Tetrahedron;
  int order = 1;
  int n = 4;                  ///< cubes per side
  bool perturbed = false;     ///< random interior-vertex perturbation (non-uniform mesh)
  /// "auto" (the default): the fastest solver for the system
  /// (solver/solver_choice.hpp) and, when that is iterative, a tolerance tied to
  /// the expected discretisation error (mms_algebraic_tolerance). Distributed
  /// runs solve with solver.distributed on hypre.
  SolverSpec solver;
  std::string vtu;            ///< if set, write the solution (displacement, error) to this .vtu file
  /// > 0: Newton's residual tolerance and the linear one (iterative solvers)
  /// instead of the defaults (1e-10, or mms_algebraic_tolerance for "auto").
  double algebraic_rtol = 0.0;
  /// Distributed over the MPI ranks (StaticOptions::distributed).
  bool distributed = false;
  /// If set: write the solved system as MatrixMarket files PREFIX*.mtx
  /// (study/mms_export.hpp; linear, serial cases only). Last, so that
  /// positional initialisers of the fields above stay valid.
  std::string export_matrix{};
  VtuFormat vtu_format = VtuFormat::ascii;  ///< encoding of `vtu` (hofem mms --vtu-format)
  /// If set: the body force that balances u* (the verification suite passes the
  /// one it derives from the material's energy with sympy); otherwise
  /// equilibrium_body_force with the material's own tangent.
  MmsBodyForce body_force{};
};

struct MmsResult {
  int cells = 0, nodes = 0, dofs = 0;
  double h = 0.0;
  double l2_error = 0.0, h1_error = 0.0;
  int newton_iterations = 0;
  int linear_iterations = 0;
  bool converged = false;
  std::string linear_solver;         ///< the solver used ("auto" resolved)
  std::string linear_solver_reason;  ///< why
  double newton_rtol = 0.0;          ///< the residual tolerance the solve ran to
  /// The last load step's final |g| / (newton_rtol * force scale): <= 1 exactly
  /// when Newton met its stopping rule (static_elasticity.hpp); +inf when it
  /// stopped before measuring a force scale.
  double residual_over_tolerance = 0.0;
  double setup_seconds = 0.0, assembly_seconds = 0.0, solve_seconds = 0.0, total_seconds = 0.0;
  int quadrature_degree = 0, error_degree = 0;
  std::vector<double> newton_residuals;  ///< |g| before each Newton step, all load steps
  std::string message;
  /// Distributed runs: every rank's figures (RankStats), the same on every rank.
  std::vector<RankStats> ranks;
};

/// The problem of a case, built but not solved (run_mms solves it with Newton;
/// the solver benchmarks assemble its linear system once and time solvers on it):
/// mesh (perturbed and raised to the case's order), material, u*, the body force
/// that balances u*, Dirichlet data u = u* on the whole boundary, and the static
/// options run_mms uses (quadrature degrees, linear solver, Newton tolerance).
/// Not copyable: body_force and dirichlet refer to the members.
struct MmsProblem {
  explicit MmsProblem(const MmsCase& c);
  MmsProblem(const MmsProblem&) = delete;
  MmsProblem& operator=(const MmsProblem&) = delete;

  bool linear = true;  ///< linear elasticity (one linear solve is the whole solution)
  std::unique_ptr<Material> material;
  ManufacturedDisplacement ustar;
  Mesh mesh;  ///< empty when `piece` is set
  /// Distributed, unperturbed cases without VTU output: this rank's
  /// piece of the cube, generated directly (box_piece), so no rank builds the
  /// whole mesh; `dirichlet` then names the piece's nodes.
  std::unique_ptr<DistributedMesh> piece;
  double h = 0.0;
  VectorField body_force;
  std::vector<DirichletCondition> dirichlet;
  StaticOptions options;
};

struct MmsErrors {
  double l2 = 0.0, h1 = 0.0;
  int degree = 0;          ///< degree of the error quadrature, >= p + 3
  Eigen::MatrixXd cell_l2;  ///< 1 x elements: per-element L2 error (for VTU output)
};

/// L2 and H1-seminorm errors of a nodal displacement u (3 * num_nodes) against
/// u*, integrated over the isoparametric map with a rule of degree >= p + 3.
MmsErrors mms_errors(const Mesh& mesh, const ManufacturedDisplacement& ustar, const Eigen::VectorXd& u);

/// Residual tolerance (Newton's |g| <= rtol * force scale, which a linear problem
/// meets in its one linear solve) that keeps the algebraic error far below the
/// discretisation error of order p on cubes of side h: 0.01 (h / L)^(p + 1), L = 1
/// the cube's side, within [1e-10, 1e-5]. Measured (L2 error against CHOLMOD's on
/// the same mesh, CG + pmg): the relative change of the L2 error is 0.004-0.013
/// times rtol / h^(p+1) -- P3 n = 12 (h^4 = 4.8e-5): rtol 1e-6 moves it 8.6e-5,
/// 1e-5 moves it 1.2e-3; P2 n = 16 (h^3 = 2.4e-4): 1e-5 moves it 5.2e-4, 1e-4
/// moves it 5.5e-3 -- so 0.01 h^(p+1) keeps it near 1e-4, ~100x inside the 1 % the
/// solver switch may cost (every study row checks it: mms.solver_switch). The
/// error constants of u* (L2 error / h^(p+1) = 0.13-0.4) are what make
/// (h / L)^(p + 1) the right scale here; a problem of unknown error keeps
/// Newton's own tolerance.
double mms_algebraic_tolerance(double h, int order);

MmsResult run_mms(const MmsCase& c);

}  // namespace hofem
