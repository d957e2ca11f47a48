#include "dense_eigenvalues.hpp"

#include <stdexcept>
#include <vector>

// LAPACK's Fortran interface, as exported by OpenBLAS (cmake/HofemDependencies.cmake).
extern "C" void dsyevd_(const char* jobz, const char* uplo, const int* n, double* a, const int* lda, double* w,
                        double* work, const int* lwork, int* iwork, const int* liwork, int* info);

namespace hofem::verification {

std::optional<Eigen::VectorXd> symmetric_eigenvalues(const Eigen::MatrixXd& A) {
  if (A.rows() != A.cols()) throw std::invalid_argument("symmetric_eigenvalues: the matrix must be square");
  const int n = static_cast<int>(A.rows());
  if (n == 0) return Eigen::VectorXd();
  Eigen::MatrixXd a = A;  // overwritten by dsyevd
  Eigen::VectorXd w(n);
  // Workspace query first (lwork = liwork = -1), then the solve.
  int lwork = -1, liwork = -1, info = 0, iwork_size = 0;
  double work_size = 0.0;
  dsyevd_("N", "L", &n, a.data(), &n, w.data(), &work_size, &lwork, &iwork_size, &liwork, &info);
  if (info != 0) return std::nullopt;
  lwork = static_cast<int>(work_size);
  liwork = iwork_size;
  std::vector<double> work(static_cast<size_t>(lwork));
  std::vector<int> iwork(static_cast<size_t>(liwork));
  dsyevd_("N", "L", &n, a.data(), &n, w.data(), work.data(), &lwork, iwork.data(), &liwork, &info);
  if (info != 0) return std::nullopt;  // > 0: an eigenvalue failed to converge
  return w;
}

}  // namespace hofem::verification
