#include "parallel/halo.hpp"

#include "parallel/collectives.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

namespace hofem {

Halo::Halo(MPI_Comm comm, const std::vector<std::int64_t>& ids, const std::vector<int>& owner, int block)
    : comm_(comm), block_(block) {
  int rank = 0, size = 1;
  MPI_Comm_rank(comm_, &rank);
  MPI_Comm_size(comm_, &size);
  if (ids.size() != owner.size() || block < 1)
    throw std::invalid_argument(fmt::format("Halo: {} ids for {} owners, block {}", ids.size(), owner.size(), block));
  owned_.resize(ids.size());
  // My ghosts, grouped by owner, ascending id within a group: the order both
  // sides use for the values of that pair.
  std::vector<std::vector<std::pair<std::int64_t, int>>> wanted(size);
  std::vector<std::pair<std::int64_t, int>> mine;
  for (size_t i = 0; i < ids.size(); ++i) {
    if (owner[i] < 0 || owner[i] >= size)
      throw std::invalid_argument(fmt::format("Halo: entry {} has owner {} outside [0, {})", i, owner[i], size));
    owned_[i] = owner[i] == rank;
    if (owned_[i]) mine.emplace_back(ids[i], static_cast<int>(i));
    else wanted[owner[i]].emplace_back(ids[i], static_cast<int>(i));
  }
  std::sort(mine.begin(), mine.end());
  std::vector<int> send_counts(size), recv_counts(size);
  for (int q = 0; q < size; ++q) {
    std::sort(wanted[q].begin(), wanted[q].end());
    send_counts[q] = static_cast<int>(wanted[q].size());
    ghosts_ += send_counts[q];
  }
  MPI_Alltoall(send_counts.data(), 1, MPI_INT, recv_counts.data(), 1, MPI_INT, comm_);
  std::vector<int> send_displs(size + 1, 0), recv_displs(size + 1, 0);
  for (int q = 0; q < size; ++q) {
    send_displs[q + 1] = send_displs[q] + send_counts[q];
    recv_displs[q + 1] = recv_displs[q] + recv_counts[q];
  }
  std::vector<std::int64_t> send_ids(send_displs[size]), recv_ids(recv_displs[size]);
  for (int q = 0; q < size; ++q)
    for (int k = 0; k < send_counts[q]; ++k) send_ids[send_displs[q] + k] = wanted[q][k].first;
  MPI_Alltoallv(send_ids.data(), send_counts.data(), send_displs.data(), MPI_INT64_T, recv_ids.data(),
                recv_counts.data(), recv_displs.data(), MPI_INT64_T, comm_);
  std::string missing;
  for (int q = 0; q < size; ++q) {
    if (send_counts[q] == 0 && recv_counts[q] == 0) continue;
    neighbour_.push_back(q);
    std::vector<int>& ghost = ghost_of_.emplace_back();
    for (const auto& w : wanted[q]) ghost.push_back(w.second);
    std::vector<int>& shared = shared_with_.emplace_back();
    for (int k = recv_displs[q]; k < recv_displs[q + 1]; ++k) {
      const auto it = std::lower_bound(mine.begin(), mine.end(), std::make_pair(recv_ids[k], -1));
      if (it == mine.end() || it->first != recv_ids[k]) {
        if (missing.empty()) missing = fmt::format("rank {} asks rank {} for id {}, which it does not own", q, rank, recv_ids[k]);
        continue;
      }
      shared.push_back(it->second);
    }
  }
  // Every rank learns whether the ownership was inconsistent anywhere, so none waits in a later exchange.
  if (any_rank(!missing.empty(), comm_))
    throw std::logic_error("Halo: inconsistent ownership: " + (missing.empty() ? std::string("on another rank") : missing));
  send_.resize(neighbour_.size());
  recv_.resize(neighbour_.size());
}

void Halo::exchange(const Eigen::VectorXd& from, Eigen::VectorXd& to, bool to_owner) const {
  if (from.size() != static_cast<Eigen::Index>(block_) * size())
    throw std::invalid_argument(fmt::format("Halo: a vector of {} values for {} entries of {}", from.size(), size(), block_));
  const int n = neighbours();
  std::vector<MPI_Request>& requests = requests_;
  requests.resize(2 * static_cast<size_t>(n));
  for (int k = 0; k < n; ++k) {
    const std::vector<int>& out = to_owner ? ghost_of_[k] : shared_with_[k];
    const std::vector<int>& in = to_owner ? shared_with_[k] : ghost_of_[k];
    recv_[k].resize(in.size() * block_);
    MPI_Irecv(recv_[k].data(), static_cast<int>(recv_[k].size()), MPI_DOUBLE, neighbour_[k], 7, comm_, &requests[2 * k]);
    send_[k].resize(out.size() * block_);
    for (size_t i = 0; i < out.size(); ++i)
      for (int c = 0; c < block_; ++c) send_[k][i * block_ + c] = from[static_cast<Eigen::Index>(out[i]) * block_ + c];
    MPI_Isend(send_[k].data(), static_cast<int>(send_[k].size()), MPI_DOUBLE, neighbour_[k], 7, comm_, &requests[2 * k + 1]);
    bytes_sent_ += 8LL * static_cast<long long>(send_[k].size());
  }
  MPI_Waitall(static_cast<int>(requests.size()), requests.data(), MPI_STATUSES_IGNORE);
  ++exchanges_;
  // Received values, in neighbour order (deterministic): added by owners, copied by ghosts.
  for (int k = 0; k < n; ++k) {
    const std::vector<int>& in = to_owner ? shared_with_[k] : ghost_of_[k];
    for (size_t i = 0; i < in.size(); ++i)
      for (int c = 0; c < block_; ++c) {
        double& slot = to[static_cast<Eigen::Index>(in[i]) * block_ + c];
        slot = to_owner ? slot + recv_[k][i * block_ + c] : recv_[k][i * block_ + c];
      }
  }
}

void Halo::sum(Eigen::VectorXd& v) const {
  exchange(v, v, true);
  update_ghosts(v);
}

void Halo::update_ghosts(Eigen::VectorXd& v) const { exchange(v, v, false); }

double Halo::dot(const Eigen::VectorXd& a, const Eigen::VectorXd& b) const {
  if (a.size() != b.size() || a.size() != static_cast<Eigen::Index>(block_) * size())
    throw std::invalid_argument(fmt::format("Halo::dot: vectors of {} and {} values for {} entries of {}", a.size(),
                                            b.size(), size(), block_));
  double local = 0.0;
  for (int i = 0; i < size(); ++i)
    if (owned_[i])
      for (int c = 0; c < block_; ++c) local += a[i * block_ + c] * b[i * block_ + c];
  return sum_over_ranks(local, comm_);
}

double Halo::norm(const Eigen::VectorXd& a) const { return std::sqrt(dot(a, a)); }

}  // namespace hofem
