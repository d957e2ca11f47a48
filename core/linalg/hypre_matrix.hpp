#pragma once
// Our matrices and vectors as hypre objects: the IJ interface builds a ParCSR
// matrix (hypre's distributed CSR, the input of BoomerAMG and hypre's Krylov
// solvers) from a SparseMatrix. Here every row is owned by the one calling rank;
// the MPI-distributed assembly will build its own HypreMatrix from
// locally owned rows, and the solvers only ever see parcsr().
//
// hypre is an MPI build: ensure_hypre() (parallel/mpi_runtime.hpp) runs before the
// first object is made. All objects are destroyed by their owner's destructor.
#include "linalg/sparse_matrix.hpp"

#include <HYPRE.h>
#include <HYPRE_IJ_mv.h>
#include <HYPRE_parcsr_mv.h>
#include <Eigen/Core>

#include <string>
#include <vector>

namespace hofem {

/// Throws std::runtime_error naming `what` and hypre's description of the error
/// if `code` (a HYPRE_* return value) is non-zero, after clearing hypre's global
/// error flag so that the next call starts clean.
void hypre_check(HYPRE_Int code, const char* what);

/// Why A cannot go to hypre, or "" if it can: A must be square, small enough for
/// hypre's 32-bit indices (Debian's build: HYPRE_Int = HYPRE_BigInt = int), with
/// finite values and a positive diagonal (every smoother divides by it).
std::string hypre_matrix_problem(const SparseMatrix& A);

/// An HYPRE_IJMatrix (ParCSR storage) of a serial matrix: all rows on this rank,
/// communicator MPI_COMM_SELF (so that every rank of an MPI run may hold its own
/// serial system without mixing them up).
class HypreMatrix {
 public:
  HypreMatrix() = default;
  ~HypreMatrix();
  HypreMatrix(const HypreMatrix&) = delete;
  HypreMatrix& operator=(const HypreMatrix&) = delete;

  /// Copies A (call hypre_matrix_problem first) into a new IJ matrix.
  ///
  /// Always a new one: hypre can re-open an assembled matrix for new values
  /// (HYPRE_IJMatrixInitialize, then SetValues), but then finds each column by a
  /// linear search of its row (IJMatrix_parcsr.c), dearer than building anew.
  /// Measured 2026-11-22 (shared/machine.md), thread CPU time, best of 5:
  ///   P1 tet, 104,544 rows, 4.5 M nonzeros: values only 0.089 s, new 0.031 s
  ///   P2 tet, 104,544 rows, 8.5 M nonzeros: values only 0.363 s, new 0.049 s
  /// next to BoomerAMG set-ups of ~1.0 s on these matrices (boomeramg.cpp).
  void assign(const SparseMatrix& A);
  HYPRE_ParCSRMatrix parcsr() const { return parcsr_; }

 private:
  void destroy();

  HYPRE_IJMatrix ij_ = nullptr;
  HYPRE_ParCSRMatrix parcsr_ = nullptr;
};

/// An HYPRE_IJVector (ParVector) laid out like the rows of a ParCSR matrix, with
/// copies of the locally owned part in and out of Eigen.
class HypreVector {
 public:
  HypreVector() = default;
  ~HypreVector();
  HypreVector(const HypreVector&) = delete;
  HypreVector& operator=(const HypreVector&) = delete;

  /// (Re)creates the vector with A's communicator and row range, all zero; no-op
  /// if it already has them.
  void conform(HYPRE_ParCSRMatrix A);
  /// Local part from / to v (v has as many entries as this rank owns rows).
  void set(const Eigen::Ref<const Eigen::VectorXd>& v);
  void get(Eigen::VectorXd& v) const;
  void set_zero();
  HYPRE_ParVector par() const { return par_; }
  HYPRE_Int local_size() const { return static_cast<HYPRE_Int>(ids_.size()); }

 private:
  void destroy();

  HYPRE_IJVector ij_ = nullptr;
  HYPRE_ParVector par_ = nullptr;
  MPI_Comm comm_ = MPI_COMM_NULL;
  std::vector<HYPRE_BigInt> ids_;  // global indices of the local rows, for Set/GetValues
};

/// Global inner product (an MPI reduction over the matrix's communicator).
double hypre_dot(const HypreVector& x, const HypreVector& y);

}  // namespace hofem
