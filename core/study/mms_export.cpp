#include "study/mms_export.hpp"

#include "assembly/assembler.hpp"
#include "io/matrix_market.hpp"
#include "material/material.hpp"

#include <fmt/format.h>

#include <stdexcept>

namespace hofem {

void export_mms_system(const MmsCase& c, const MmsProblem& p, const StaticElasticity& solved,
                       const std::string& prefix) {
  // A nonlinear problem has one system per Newton step, none of them "the" system.
  if (!p.linear)
    throw std::invalid_argument(fmt::format(
        "--export-matrix: problem '{}' is nonlinear (one system per Newton step); export the linear problem",
        c.problem));
  if (p.piece || c.distributed)
    throw std::invalid_argument("--export-matrix: serial runs only (a distributed system lives on several ranks)");
  const Mesh& mesh = solved.mesh();
  const DofMap& dofs = solved.dofs();
  const Assembler& a = solved.assembler();
  // Linear elasticity: the Hessian is K at any state; its gradient at u_c on the
  // constrained DOFs (free DOFs zero) is K_{., c} u_c, so f - g restricted to the
  // free DOFs is the eliminated right-hand side.
  Eigen::VectorXd u_constrained = solved.displacement();
  for (int dof : dofs.free_dofs()) u_constrained[dof] = 0.0;
  const Eigen::VectorXd x = Eigen::Map<const Eigen::VectorXd>(mesh.nodes.data(), 3 * mesh.num_nodes()) + u_constrained;
  Eigen::VectorXd g;
  SparseMatrix K = a.new_matrix();
  a.hessian(*p.material, x, g, K, false);
  const Eigen::VectorXd b = dofs.restrict(a.body_force_vector(p.body_force, p.options.load_degree) - g);

  const std::vector<std::string> about = {
      fmt::format("hofem mms --problem {} --cell {} --order {} --n {}{}", c.problem, name(c.cell), c.order, c.n,
                  c.perturbed ? " --perturbed" : ""),
      "Dirichlet conditions u = u* on every boundary node, eliminated: the constrained DOFs' rows and",
      "columns are removed and their values moved to the right-hand side, b = f_f - K_fc u_c.",
      fmt::format("{} unknowns: the free DOFs 3 * node + component in increasing order ({} DOFs in all).",
                  dofs.num_free(), dofs.num_dofs()),
      fmt::format("quadrature degree {} (stiffness), {} (load); material linear, E = 1, nu = 0.3.",
                  p.options.quadrature_degree, p.options.load_degree)};
  auto with = [&about](const std::string& what) {
    std::vector<std::string> lines = about;
    lines.insert(lines.begin(), what);
    return lines;
  };
  write_matrix_market(prefix + ".mtx", K, with("K_ff, the stiffness matrix as solved (symmetric, stored in full)"));
  write_matrix_market(prefix + "_rhs.mtx", b, with("b, the right-hand side as solved"));
  write_matrix_market(prefix + "_solution.mtx", dofs.restrict(solved.displacement()),
                      with(fmt::format("u_f, hofem's solution of K u = b (solved to |K u - b| <= {:g} x the force scale)",
                                       p.options.newton.rtol)));
}

}  // namespace hofem
