// The names of the linear solvers, preconditioners and BoomerAMG variants, in a
// file of their own without the solvers: the scene reader validates names with
// them, and its sanitized test build (verification/unit/CMakeLists.txt) should
// not need hypre, CHOLMOD and every preconditioner to link.
#include "solver/preconditioner.hpp"
#include "solver/solver_spec.hpp"

#include <string>
#include <vector>

namespace hofem {

std::vector<std::string> boomeramg_variant_names() { return {"amg", "amg-nodal", "amg-aggressive"}; }

std::vector<std::string> preconditioner_names() {
  std::vector<std::string> names{"none", "jacobi", "block-jacobi", "ic0", "eigen-ict"};
  for (const std::string& v : boomeramg_variant_names()) names.push_back(v);
  names.insert(names.end(), {"pmg", "schwarz"});
  return names;
}

std::vector<std::string> linear_solver_names() {
  std::vector<std::string> names{"cholmod", "umfpack", "eigen-ldlt", "hypre-pcg+amg"};
  for (const char* method : {"cg", "cr", "minres", "gmres"})
    for (const std::string& pc : preconditioner_names()) names.push_back(std::string(method) + "+" + pc);
  return names;
}

}  // namespace hofem
