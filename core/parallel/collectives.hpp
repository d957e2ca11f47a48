#pragma once
// The few collectives a distributed problem needs on top of its serial code:
// each rank integrates its own elements, so energies and force
// vectors are sums over ranks, and a failure on one rank (an inverted element
// in its part) must stop every rank at the same point, not leave the others
// waiting in the next collective.
#include <Eigen/Core>
#include <mpi.h>

#include <string>

namespace hofem {

double sum_over_ranks(double value, MPI_Comm comm);
int sum_over_ranks(int value, MPI_Comm comm);
/// In place; every rank ends with the same (bitwise) sum.
void sum_over_ranks(Eigen::Ref<Eigen::VectorXd> values, MPI_Comm comm);
double min_over_ranks(double value, MPI_Comm comm);
double max_over_ranks(double value, MPI_Comm comm);
/// True on every rank if it is true on any.
bool any_rank(bool flag, MPI_Comm comm);

/// Runs f. Distributed: every rank then learns whether f threw E on any rank,
/// and if so all throw E together - the failing rank with its own message, the
/// others with E(what) - so that none is left waiting in the next collective.
/// Serial: f runs and its exceptions pass unchanged.
template <class E, class F>
void on_all_ranks_or_throw(bool distributed, MPI_Comm comm, const char* what, F&& f) {
  if (!distributed) {
    f();
    return;
  }
  bool failed = false;
  std::string message = what;
  try {
    f();
  } catch (const E& e) {
    failed = true;
    message = e.what();
  }
  if (any_rank(failed, comm)) throw E(message);
}

}  // namespace hofem
