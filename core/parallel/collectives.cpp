#include "parallel/collectives.hpp"

namespace hofem {

namespace {

template <class T>
T reduce(T value, MPI_Datatype type, MPI_Op op, MPI_Comm comm) {
  T result{};
  MPI_Allreduce(&value, &result, 1, type, op, comm);
  return result;
}

}  // namespace

double sum_over_ranks(double value, MPI_Comm comm) { return reduce(value, MPI_DOUBLE, MPI_SUM, comm); }
int sum_over_ranks(int value, MPI_Comm comm) { return reduce(value, MPI_INT, MPI_SUM, comm); }
double min_over_ranks(double value, MPI_Comm comm) { return reduce(value, MPI_DOUBLE, MPI_MIN, comm); }
double max_over_ranks(double value, MPI_Comm comm) { return reduce(value, MPI_DOUBLE, MPI_MAX, comm); }

void sum_over_ranks(Eigen::Ref<Eigen::VectorXd> values, MPI_Comm comm) {
  MPI_Allreduce(MPI_IN_PLACE, values.data(), static_cast<int>(values.size()), MPI_DOUBLE, MPI_SUM, comm);
}

bool any_rank(bool flag, MPI_Comm comm) { return reduce(flag ? 1 : 0, MPI_INT, MPI_LOR, comm) != 0; }

}  // namespace hofem
