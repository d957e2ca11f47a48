#pragma once
// The sparse matrix type at the boundary between assembly and linear algebra:
// compressed columns with 64-bit indices (CHOLMOD's long interface takes the
// arrays as they are; an MPI path can replace it with hypre's ParCSR later
// without touching elements or materials). Symmetric matrices are stored in full.
#include <Eigen/SparseCore>

#include <cstdint>

namespace hofem {

using SparseMatrix = Eigen::SparseMatrix<double, Eigen::ColMajor, std::int64_t>;

}  // namespace hofem
