#include "linalg/incomplete_cholesky.hpp"

#include <cmath>
#include <vector>

namespace hofem {

bool IncompleteCholesky0::compute(const SparseMatrix& A) {
  SparseMatrix lower_a = A.triangularView<Eigen::Lower>();
  lower_a.makeCompressed();
  double alpha = 0.0;
  for (int restart = 0; restart <= 20; ++restart) {
    if (factorize(lower_a, alpha)) {
      shift_ = alpha;
      return true;
    }
    alpha = alpha == 0.0 ? 1e-3 : 2.0 * alpha;
  }
  return false;
}

// Right-looking column IC(0) on the lower pattern (rows ascending in each column,
// the diagonal first): column k is scaled by its pivot's square root, then every
// later column i with L(i, k) != 0 loses L(j, k) L(i, k) at the rows j >= i it
// already holds (a row marker of column i maps row -> position; rows it does not
// hold are fill, dropped).
bool IncompleteCholesky0::factorize(const SparseMatrix& lower_a, double alpha) {
  L_ = lower_a;
  const Eigen::Index n = L_.cols();
  const std::int64_t* start = L_.outerIndexPtr();
  const std::int64_t* row = L_.innerIndexPtr();
  double* val = L_.valuePtr();
  for (Eigen::Index k = 0; k < n; ++k)
    if (start[k] == start[k + 1] || row[start[k]] != k) return false;  // a missing diagonal: no IC(0)
  if (alpha > 0.0)
    for (Eigen::Index k = 0; k < n; ++k) val[start[k]] *= 1.0 + alpha;
  std::vector<std::int64_t> position(static_cast<size_t>(n), -1);
  for (Eigen::Index k = 0; k < n; ++k) {
    const double pivot = val[start[k]];
    if (!(pivot > 0.0) || !std::isfinite(pivot)) return false;
    const double d = std::sqrt(pivot);
    val[start[k]] = d;
    for (std::int64_t p = start[k] + 1; p < start[k + 1]; ++p) val[p] /= d;
    for (std::int64_t p = start[k] + 1; p < start[k + 1]; ++p) {
      const Eigen::Index i = row[p];
      const double lik = val[p];
      for (std::int64_t q = start[i]; q < start[i + 1]; ++q) position[row[q]] = q;
      for (std::int64_t r = p; r < start[k + 1]; ++r)  // rows j >= i of column k
        if (const std::int64_t q = position[row[r]]; q >= 0) val[q] -= val[r] * lik;
      for (std::int64_t q = start[i]; q < start[i + 1]; ++q) position[row[q]] = -1;
    }
  }
  return true;
}

void IncompleteCholesky0::solve(const Eigen::VectorXd& r, Eigen::VectorXd& z) const {
  const Eigen::Index n = L_.cols();
  const std::int64_t* start = L_.outerIndexPtr();
  const std::int64_t* row = L_.innerIndexPtr();
  const double* val = L_.valuePtr();
  z = r;
  for (Eigen::Index k = 0; k < n; ++k) {  // L y = r, by columns
    z[k] /= val[start[k]];
    for (std::int64_t p = start[k] + 1; p < start[k + 1]; ++p) z[row[p]] -= val[p] * z[k];
  }
  for (Eigen::Index k = n - 1; k >= 0; --k) {  // L^T z = y: row k of L^T is column k of L
    double s = z[k];
    for (std::int64_t p = start[k] + 1; p < start[k + 1]; ++p) s -= val[p] * z[row[p]];
    z[k] = s / val[start[k]];
  }
}

}  // namespace hofem
