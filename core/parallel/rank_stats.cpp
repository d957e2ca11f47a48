#include "parallel/rank_stats.hpp"

#include <type_traits>

namespace hofem {

std::vector<RankStats> gather_rank_stats(const RankStats& mine, MPI_Comm comm) {
  static_assert(std::is_trivially_copyable_v<RankStats>);
  int ranks = 1;
  MPI_Comm_size(comm, &ranks);
  std::vector<RankStats> all(ranks);
  MPI_Allgather(&mine, sizeof(RankStats), MPI_BYTE, all.data(), sizeof(RankStats), MPI_BYTE, comm);
  return all;
}

nlohmann::json to_json(const std::vector<RankStats>& ranks) {
  nlohmann::json out = nlohmann::json::array();
  for (const RankStats& s : ranks)
    out.push_back({{"rank", s.rank},
                   {"elements", s.elements},
                   {"local_nodes", s.local_nodes},
                   {"owned_nodes", s.owned_nodes},
                   {"ghost_nodes", s.ghost_nodes},
                   {"neighbours", s.neighbours},
                   {"owned_rows", s.owned_rows},
                   {"local_free_dofs", s.local_free_dofs},
                   {"pattern_nonzeros", s.pattern_nonzeros},
                   {"matrix_nonzeros", s.matrix_nonzeros},
                   {"matvec_receive_values", s.matvec_receive_values},
                   {"matvec_receive_bytes", 8 * s.matvec_receive_values},
                   {"halo_exchanges", s.halo_exchanges},
                   {"halo_bytes_sent", s.halo_bytes_sent},
                   {"amg_setups", s.amg_setups},
                   {"krylov_solves", s.krylov_solves},
                   {"krylov_iterations", s.krylov_iterations},
                   {"ij_seconds", s.ij_seconds},
                   {"amg_setup_seconds", s.amg_setup_seconds},
                   {"krylov_seconds", s.krylov_seconds}});
  return out;
}

}  // namespace hofem
