#include "solver/block_galerkin.hpp"

#include <algorithm>
#include <stdexcept>

namespace hofem {

BlockSparseMatrix<double> galerkin_structure(const BlockSparseMatrix<double>& A, const NodeTransfer& t) {
  if (A.block_rows() != t.P.rows()) throw std::invalid_argument("BlockGalerkin: matrix and transfer sizes differ");
  const Eigen::Index nc = t.P.cols();
  const RowSparseMatrix& P = t.P;
  const RowSparseMatrix& R = t.R;
  std::vector<std::vector<std::int32_t>> rows(static_cast<size_t>(nc));
#pragma omp parallel if (nc >= 2000)
  {
    std::vector<Eigen::Index> mark(static_cast<size_t>(nc), -1);
#pragma omp for schedule(dynamic, 64)
    for (Eigen::Index I = 0; I < nc; ++I) {
      std::vector<std::int32_t>& cols = rows[I];
      for (RowSparseMatrix::InnerIterator rk(R, I); rk; ++rk)
        for (std::int32_t q = A.row_start()[rk.col()]; q < A.row_start()[rk.col() + 1]; ++q)
          for (RowSparseMatrix::InnerIterator pl(P, A.column()[q]); pl; ++pl)
            if (mark[pl.col()] != I) {
              mark[pl.col()] = I;
              cols.push_back(static_cast<std::int32_t>(pl.col()));
            }
      std::sort(cols.begin(), cols.end());
    }
  }
  std::vector<std::int32_t> start(static_cast<size_t>(nc) + 1, 0), column;
  for (Eigen::Index I = 0; I < nc; ++I) start[I + 1] = start[I] + static_cast<std::int32_t>(rows[I].size());
  column.reserve(static_cast<size_t>(start[nc]));
  for (const auto& r : rows) column.insert(column.end(), r.begin(), r.end());
  return BlockSparseMatrix<double>(std::move(start), std::move(column));
}

void galerkin_values(const BlockSparseMatrix<double>& A, const NodeTransfer& t, BlockSparseMatrix<double>& Ac) {
  const Eigen::Index nc = t.P.cols();
  if (Ac.block_rows() != nc || A.block_rows() != t.P.rows())
    throw std::invalid_argument("BlockGalerkin::compute: sizes do not match the analysed product");
  const RowSparseMatrix& P = t.P;
  const RowSparseMatrix& R = t.R;
#pragma omp parallel if (nc >= 2000)
  {
    std::vector<std::int32_t> position(static_cast<size_t>(nc), -1);  // coarse column -> block of row I
#pragma omp for schedule(dynamic, 64)
    for (Eigen::Index I = 0; I < nc; ++I) {
      const std::int32_t begin = Ac.row_start()[I], end = Ac.row_start()[I + 1];
      for (std::int32_t k = begin; k < end; ++k) position[Ac.column()[k]] = k;
      std::fill(Ac.block_values(begin), Ac.block_values(end), 0.0);
      for (RowSparseMatrix::InnerIterator rk(R, I); rk; ++rk)
        for (std::int32_t q = A.row_start()[rk.col()]; q < A.row_start()[rk.col() + 1]; ++q) {
          const double* a = A.block_values(q);
          for (RowSparseMatrix::InnerIterator pl(P, A.column()[q]); pl; ++pl) {
            const double w = rk.value() * pl.value();
            double* c = Ac.block_values(position[pl.col()]);
            for (int v = 0; v < 9; ++v) c[v] += w * a[v];
          }
        }
    }
  }
}

}  // namespace hofem
