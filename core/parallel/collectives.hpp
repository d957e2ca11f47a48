#pragma once
// The few collectives a distributed problem needs on top of its serial code
// (issue 7): each rank integrates its own elements, so energies and force
// vectors are sums over ranks, and a failure on one rank (an inverted element
// in its part) must stop every rank at the same point, not leave the others
// waiting in the next collective.
#include <Eigen/Core>
#include <mpi.h>

namespace hofem {

double sum_over_ranks(double value, MPI_Comm comm);
/// In place; every rank ends with the same (bitwise) sum.
void sum_over_ranks(Eigen::VectorXd& values, MPI_Comm comm);
/// True on every rank if it is true on any.
bool any_rank(bool flag, MPI_Comm comm);

}  // namespace hofem
