#pragma once
// Owned and ghost entries of a distributed vector, and the two exchanges a
// distributed finite element code needs:
//  - sum(): every rank integrated its own elements, so an entry on a part
//    boundary holds only a partial sum on each rank that touches it; ghosts send
//    their partial values to the owner, which adds them, and the owner's total
//    goes back, so every copy ends as the full (and bitwise equal) sum;
//  - update_ghosts(): the owner's value is copied to the ghosts (after a solve,
//    which only computes the owned rows).
// A vector in which every ghost equals its owner's value is "consistent"; the
// distributed problems keep their state and their gradients consistent, so that
// Newton's decisions (dot(): owned entries only, summed over ranks) agree on
// every rank.
//
// The exchanges are point-to-point with the neighbouring ranks only (those
// sharing an entry), so their cost is the halo, not the number of ranks; the
// counters measure the communication volume the issue asks for.
#include <Eigen/Core>
#include <mpi.h>

#include <cstdint>
#include <vector>

namespace hofem {

class Halo {
 public:
  /// Collective. ids: the global id of each local entry (a node, or a DOF);
  /// owner: its owning rank. `block` values per entry in the vectors (3 for a
  /// vector of node displacements, 1 for a vector of DOFs). Throws
  /// std::invalid_argument for mismatched sizes or an owner outside the
  /// communicator, std::logic_error if an owner does not have a ghost's id.
  Halo(MPI_Comm comm, const std::vector<std::int64_t>& ids, const std::vector<int>& owner, int block = 1);

  /// Partial sums in, full sums out (every copy of an entry equal).
  void sum(Eigen::VectorXd& v) const;
  /// The owners' values copied to the ghosts.
  void update_ghosts(Eigen::VectorXd& v) const;
  /// Sum over ranks of the owned entries' a_i b_i (the global dot product of
  /// consistent vectors); the same value on every rank.
  double dot(const Eigen::VectorXd& a, const Eigen::VectorXd& b) const;
  double norm(const Eigen::VectorXd& a) const;

  bool owned(int entry) const { return owned_[entry] != 0; }
  int size() const { return static_cast<int>(owned_.size()); }
  int ghosts() const { return ghosts_; }
  int neighbours() const { return static_cast<int>(neighbour_.size()); }
  int block() const { return block_; }
  MPI_Comm comm() const { return comm_; }
  /// Bytes this rank receives in one update_ghosts() (sum() moves this twice).
  long long bytes_per_update() const { return 8LL * block_ * ghosts_; }
  /// Bytes sent by this rank in all exchanges so far, and their count.
  long long bytes_sent() const { return bytes_sent_; }
  long long exchanges() const { return exchanges_; }

 private:
  // to_owner: ghosts' values travel to their owners (sum), or back (update).
  void exchange(const Eigen::VectorXd& from, Eigen::VectorXd& to, bool to_owner) const;
  MPI_Comm comm_;
  int block_ = 1, ghosts_ = 0;
  std::vector<char> owned_;
  std::vector<int> neighbour_;                 ///< ranks sharing entries with this one
  std::vector<std::vector<int>> ghost_of_;     ///< per neighbour: my ghosts it owns (in the order agreed)
  std::vector<std::vector<int>> shared_with_;  ///< per neighbour: my owned entries it ghosts (same order)
  mutable std::vector<std::vector<double>> send_, recv_;  // reused: exchanges run every Newton iteration
  mutable std::vector<MPI_Request> requests_;
  mutable long long bytes_sent_ = 0, exchanges_ = 0;
};

}  // namespace hofem
