#include "problem/rank_figures.hpp"

#include "solver/distributed_system.hpp"

namespace hofem {

RankStats rank_stats(const DistributedMesh& mesh, const DistributedDofs& rows, const Assembler& assembler,
                     const LinearSolver& solver) {
  RankStats s;
  s.rank = mesh.rank;
  s.elements = mesh.local.mesh.num_elements();
  s.local_nodes = mesh.local.mesh.num_nodes();
  s.owned_nodes = mesh.local.owned_nodes();
  s.ghost_nodes = s.local_nodes - s.owned_nodes;
  s.neighbours = mesh.nodes.neighbours();
  s.owned_rows = rows.owned_rows;
  s.local_free_dofs = static_cast<long long>(rows.row.size());
  s.pattern_nonzeros = assembler.pattern().nonzeros();
  s.halo_exchanges = mesh.nodes.exchanges() + rows.free.exchanges();
  s.halo_bytes_sent = mesh.nodes.bytes_sent() + rows.free.bytes_sent();
  if (const auto* hypre = dynamic_cast<const DistributedHypreSolver*>(&solver)) {
    const DistributedLinearSystem& system = hypre->system();
    s.matrix_nonzeros = system.local_nonzeros();
    s.matvec_receive_values = system.matvec_receive_values();
    const auto& t = system.timings();
    s.amg_setups = t.setups;
    s.krylov_solves = t.solves;
    s.krylov_iterations = t.iterations;
    s.ij_seconds = t.ij_seconds;
    s.amg_setup_seconds = t.amg_seconds;
    s.krylov_seconds = t.krylov_seconds;
  }
  return s;
}

}  // namespace hofem
