#pragma once
// The preconditioners that need the matrix only (thesis §3.1): z = M^-1 r with
// M the identity ("none"), A's diagonal ("jacobi"), its 3x3 nodal blocks
// ("block-jacobi"), IC(0) with zero fill (thesis Algorithm 2, diagonal shift
// retried on breakdown: linalg/incomplete_cholesky.hpp) or Eigen's
// memory-limited incomplete Cholesky (Lin and More; "eigen-ict"). BoomerAMG is
// in linalg/boomeramg.hpp; the registry that names them all is
// solver/solver_registry.cpp.
#include "linalg/preconditioner.hpp"

#include <memory>

namespace hofem {

std::unique_ptr<Preconditioner> make_identity_preconditioner();
std::unique_ptr<Preconditioner> make_jacobi_preconditioner();
std::unique_ptr<Preconditioner> make_block_jacobi_preconditioner();
std::unique_ptr<Preconditioner> make_ic0_preconditioner();
std::unique_ptr<Preconditioner> make_eigen_ict_preconditioner();

}  // namespace hofem
