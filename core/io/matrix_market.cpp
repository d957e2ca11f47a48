#include "io/matrix_market.hpp"

#include "io/atomic_file.hpp"

#include <fmt/format.h>

namespace hofem {
namespace {

std::string header(const char* format, const std::vector<std::string>& comments) {
  std::string text = fmt::format("%%MatrixMarket matrix {} real general\n", format);
  for (const std::string& line : comments) text += fmt::format("% {}\n", line);
  return text;
}

}  // namespace

void write_matrix_market(const std::string& path, const Eigen::SparseMatrix<double, Eigen::ColMajor, std::int64_t>& A,
                         const std::vector<std::string>& comments) {
  // Explicitly stored zeros are written too: the file has the assembled pattern.
  std::string text = header("coordinate", comments);
  text += fmt::format("{} {} {}\n", A.rows(), A.cols(), A.nonZeros());
  for (std::int64_t col = 0; col < A.outerSize(); ++col)
    for (Eigen::SparseMatrix<double, Eigen::ColMajor, std::int64_t>::InnerIterator it(A, col); it; ++it)
      text += fmt::format("{} {} {:.17g}\n", it.row() + 1, it.col() + 1, it.value());
  write_file_atomically(path, text);
}

void write_matrix_market(const std::string& path, const Eigen::VectorXd& v, const std::vector<std::string>& comments) {
  std::string text = header("array", comments);
  text += fmt::format("{} 1\n", v.size());
  for (Eigen::Index i = 0; i < v.size(); ++i) text += fmt::format("{:.17g}\n", v[i]);
  write_file_atomically(path, text);
}

}  // namespace hofem
