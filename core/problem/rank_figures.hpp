#pragma once
// A rank's RankStats (parallel/rank_stats.hpp) filled from what this rank
// holds: its piece of the mesh, its DOF rows, its assembler's pattern and, for
// a distributed hypre solver, the matrix and timing figures.
#include "assembly/assembler.hpp"
#include "assembly/distributed_dofs.hpp"
#include "parallel/rank_stats.hpp"
#include "linalg/linear_solver.hpp"

namespace hofem {

/// This rank's figures; `solver` may be any LinearSolver (only a distributed
/// hypre solver contributes matrix and timing figures).
RankStats rank_stats(const DistributedMesh& mesh, const DistributedDofs& rows, const Assembler& assembler,
                     const LinearSolver& solver);

}  // namespace hofem
