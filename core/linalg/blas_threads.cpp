#include "linalg/blas_threads.hpp"

#include <omp.h>

#include <algorithm>
#include <atomic>

// OpenBLAS's public thread controls (its cblas.h declares them). Declared here
// rather than included: which cblas.h /usr/include holds depends on the BLAS
// the system's alternatives point at, while hofem links OpenBLAS itself
// (cmake/HofemLibraryDependencies.cmake requires it).
extern "C" {
void openblas_set_num_threads(int num_threads);
int openblas_get_num_threads(void);
}

namespace hofem {

int use_blas_threads_for(double flops) {
  // The pool's size as OpenBLAS started (OPENBLAS_NUM_THREADS, else the cores),
  // read before the first change.
  static const int pool = std::max(1, std::min(openblas_get_num_threads(), omp_get_max_threads()));
  static std::atomic<int> current{0};
  const int wanted = flops >= kThreadedBlasMinFlops ? pool : 1;
  if (current.exchange(wanted) != wanted) openblas_set_num_threads(wanted);
  return wanted;
}

}  // namespace hofem
