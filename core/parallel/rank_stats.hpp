#pragma once
// What one rank of a distributed run holds, sends and spends: the
// per-rank figures behind the scaling report and the sizing model
// (scripts/mpi/mpi_model.py). Gathered so that rank 0 can write them all.
//
// The figures are plain counts and times, filled by the layers that know them
// (problem/rank_figures.hpp: the mesh piece, the DOF rows, the assembler and
// the hypre solver); this layer only gathers and writes them.
#include <mpi.h>
#include <nlohmann/json.hpp>

#include <vector>

namespace hofem {

struct RankStats {
  int rank = 0;
  int elements = 0, local_nodes = 0, owned_nodes = 0, ghost_nodes = 0, neighbours = 0;
  long long owned_rows = 0, local_free_dofs = 0;
  long long pattern_nonzeros = 0;       ///< the piece's sparsity pattern (local free x local free)
  long long matrix_nonzeros = 0;        ///< hypre's stored rows (owned rows, all columns)
  long long matvec_receive_values = 0;  ///< doubles received per matrix-vector product
  long long halo_exchanges = 0, halo_bytes_sent = 0;  ///< the problem's own halo traffic (forces, solutions)
  int amg_setups = 0, krylov_solves = 0;
  long long krylov_iterations = 0;
  double ij_seconds = 0.0, amg_setup_seconds = 0.0, krylov_seconds = 0.0;
};

/// Collective: every rank's figures, on every rank.
std::vector<RankStats> gather_rank_stats(const RankStats& mine, MPI_Comm comm);
nlohmann::json to_json(const std::vector<RankStats>& ranks);

}  // namespace hofem
