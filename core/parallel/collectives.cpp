#include "parallel/collectives.hpp"

namespace hofem {

double sum_over_ranks(double value, MPI_Comm comm) {
  double sum = 0.0;
  MPI_Allreduce(&value, &sum, 1, MPI_DOUBLE, MPI_SUM, comm);
  return sum;
}

void sum_over_ranks(Eigen::VectorXd& values, MPI_Comm comm) {
  MPI_Allreduce(MPI_IN_PLACE, values.data(), static_cast<int>(values.size()), MPI_DOUBLE, MPI_SUM, comm);
}

bool any_rank(bool flag, MPI_Comm comm) {
  int mine = flag ? 1 : 0, any = 0;
  MPI_Allreduce(&mine, &any, 1, MPI_INT, MPI_LOR, comm);
  return any != 0;
}

}  // namespace hofem
