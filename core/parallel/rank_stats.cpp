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

NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(RankStats, rank, elements, local_nodes, owned_nodes, ghost_nodes, neighbours,
                                   owned_rows, local_free_dofs, pattern_nonzeros, matrix_nonzeros,
                                   matvec_receive_values, halo_exchanges, halo_bytes_sent, amg_setups, krylov_solves,
                                   krylov_iterations, ij_seconds, amg_setup_seconds, krylov_seconds)

nlohmann::json to_json(const std::vector<RankStats>& ranks) {
  nlohmann::json out = nlohmann::json::array();
  for (const RankStats& s : ranks) {
    out.push_back(s);
    out.back()["matvec_receive_bytes"] = 8 * s.matvec_receive_values;
  }
  return out;
}

}  // namespace hofem
