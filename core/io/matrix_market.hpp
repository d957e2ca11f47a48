#pragma once
// MatrixMarket files (NIST's exchange format, https://math.nist.gov/MatrixMarket/formats.html),
// so a system assembled here can be loaded by another code (scipy.io.mmread,
// MATLAB's mmread, PETSc, Julia's MatrixMarket.jl) and solved there:
//   a sparse matrix as "coordinate real general" (every stored entry, 1-based
//   row and column), a vector as "array real general" (one column).
// Values are printed with %.17g, enough digits to read back the same doubles.
// Each `comments` line becomes a "%" line after the banner (what the file holds).
// Files are written atomically (io/atomic_file.hpp); errors name the path.
#include <Eigen/Core>
#include <Eigen/SparseCore>

#include <cstdint>
#include <string>
#include <vector>

namespace hofem {

void write_matrix_market(const std::string& path, const Eigen::SparseMatrix<double, Eigen::ColMajor, std::int64_t>& A,
                         const std::vector<std::string>& comments);
void write_matrix_market(const std::string& path, const Eigen::VectorXd& v, const std::vector<std::string>& comments);

}  // namespace hofem
