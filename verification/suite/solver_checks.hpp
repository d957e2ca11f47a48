#pragma once
// Linear solvers and preconditioners (thesis §3.1-3.2, §5.3.2):
//  - solvers.spd:          every linear solver and Krylov method x preconditioner
//                          on SPD elasticity systems (tet orders 1-3, Hex8, Hex20)
//                          reaches the requested residual and agrees with CHOLMOD;
//  - solvers.indefinite:   on the unprojected Neo-Hookean Hessian of a strongly
//                          compressed cube CG reports breakdown, CR/MINRES/GMRES converge;
//  - solvers.preconditioner_spd: each preconditioner is symmetric positive definite;
//  - solvers.amg_scaling:  BoomerAMG-CG iterations grow at most 1.5x over three
//                          uniform refinements (orders 1 and 2).
// The BoomerAMG rows start MPI (core/parallel/mpi_runtime.hpp).
#include "report.hpp"

namespace hofem::verification {

void add_solver_checks(Report& report);

}  // namespace hofem::verification
