// The library stack hofem builds on, linked and exercised: CHOLMOD and UMFPACK
// (SuiteSparse) solve a small SPD system, and hypre starts under MPI. Catches a
// broken install (missing OpenBLAS, MPI/hypre mismatch) before later layers do.
#include "parallel/mpi_runtime.hpp"

#include <HYPRE.h>
#include <HYPRE_utilities.h>
#include <cholmod.h>
#include <mpi.h>
#include <umfpack.h>

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace {

// 1D Laplacian, n = 50, in compressed-column form (both triangles).
struct Csc {
  int n = 50;
  std::vector<int> p, i;
  std::vector<double> x;
  Csc() {
    p.push_back(0);
    for (int c = 0; c < n; ++c) {
      if (c > 0) i.push_back(c - 1), x.push_back(-1.0);
      i.push_back(c), x.push_back(2.0);
      if (c + 1 < n) i.push_back(c + 1), x.push_back(-1.0);
      p.push_back(static_cast<int>(i.size()));
    }
  }
  // Exact solution of A u = b for u_k = sin(k): residual check instead.
  std::vector<double> apply(const std::vector<double>& u) const {
    std::vector<double> y(n, 0.0);
    for (int c = 0; c < n; ++c)
      for (int k = p[c]; k < p[c + 1]; ++k) y[i[k]] += x[k] * u[c];
    return y;
  }
};

double max_error(const std::vector<double>& a, const std::vector<double>& b) {
  double e = 0;
  for (size_t k = 0; k < a.size(); ++k) e = std::max(e, std::fabs(a[k] - b[k]));
  return e;
}

std::vector<double> reference_solution(int n) {
  std::vector<double> u(n);
  for (int k = 0; k < n; ++k) u[k] = std::sin(0.1 * k);
  return u;
}

// cond(A) ~ 1e3 for n = 50: a backward-stable direct solve recovers u to ~1e-13.
constexpr double kDirectSolveTol = 1e-11;

TEST(Dependencies, CholmodSolvesSpdSystem) {
  Csc A;
  const std::vector<double> u = reference_solution(A.n), b = A.apply(u);
  cholmod_common c;
  cholmod_start(&c);
  cholmod_sparse* S = cholmod_allocate_sparse(A.n, A.n, A.x.size(), 1, 1, 0, CHOLMOD_REAL, &c);
  std::copy(A.p.begin(), A.p.end(), static_cast<int*>(S->p));
  std::copy(A.i.begin(), A.i.end(), static_cast<int*>(S->i));
  std::copy(A.x.begin(), A.x.end(), static_cast<double*>(S->x));
  S->stype = 0;  // unsymmetric storage of a symmetric matrix
  cholmod_sparse* L = cholmod_copy(S, 1, 1, &c);  // upper triangle, stype = 1
  cholmod_factor* F = cholmod_analyze(L, &c);
  ASSERT_TRUE(cholmod_factorize(L, F, &c));
  cholmod_dense* B = cholmod_allocate_dense(A.n, 1, A.n, CHOLMOD_REAL, &c);
  std::copy(b.begin(), b.end(), static_cast<double*>(B->x));
  cholmod_dense* X = cholmod_solve(CHOLMOD_A, F, B, &c);
  const double* xs = static_cast<double*>(X->x);
  EXPECT_LE(max_error(std::vector<double>(xs, xs + A.n), u), kDirectSolveTol);
  cholmod_free_dense(&X, &c);
  cholmod_free_dense(&B, &c);
  cholmod_free_factor(&F, &c);
  cholmod_free_sparse(&L, &c);
  cholmod_free_sparse(&S, &c);
  cholmod_finish(&c);
}

TEST(Dependencies, UmfpackSolvesSystem) {
  Csc A;
  const std::vector<double> u = reference_solution(A.n), b = A.apply(u);
  void *symbolic = nullptr, *numeric = nullptr;
  ASSERT_EQ(umfpack_di_symbolic(A.n, A.n, A.p.data(), A.i.data(), A.x.data(), &symbolic, nullptr, nullptr), UMFPACK_OK);
  ASSERT_EQ(umfpack_di_numeric(A.p.data(), A.i.data(), A.x.data(), symbolic, &numeric, nullptr, nullptr), UMFPACK_OK);
  std::vector<double> x(A.n);
  ASSERT_EQ(umfpack_di_solve(UMFPACK_A, A.p.data(), A.i.data(), A.x.data(), x.data(), b.data(), numeric, nullptr, nullptr),
            UMFPACK_OK);
  EXPECT_LE(max_error(x, u), kDirectSolveTol);
  umfpack_di_free_symbolic(&symbolic);
  umfpack_di_free_numeric(&numeric);
}

// Debian's hypre is an MPI build: MPI_Init must precede HYPRE_Init.
// hofem::ensure_hypre() does both once per process (MPI_Finalize at exit), so
// the hypre tests of this binary can follow.
TEST(Dependencies, HypreInitialisesUnderMpi) {
  hofem::ensure_hypre();
  int flag = 0, size = 0;
  MPI_Initialized(&flag);
  EXPECT_TRUE(flag);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  EXPECT_GE(size, 1);
  hofem::ensure_hypre();  // idempotent
}

}  // namespace
