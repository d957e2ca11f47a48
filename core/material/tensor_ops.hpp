#pragma once
// Small fixed-size tensor helpers shared by the material models (header-only,
// inline, no allocation). Flattening as in material.hpp: vec(F)[i + 3 j] = F(i, j),
// so column j of F is entries 3j..3j+2 of vec(F) and the 3x3 block (j, l) of a
// 9x9 tangent holds d P(:, j) / d F(:, l).
#include "material/material.hpp"

#include <Eigen/Core>
#include <Eigen/Geometry>  // cross products

namespace hofem::material_detail {

using Vec3 = Eigen::Vector3d;
using Vec9 = Eigen::Matrix<double, 9, 1>;

inline Eigen::Map<const Vec9> vec(const Mat3& A) { return Eigen::Map<const Vec9>(A.data()); }

/// [v]x, the matrix with [v]x u = v x u.
inline Mat3 cross_matrix(const Vec3& v) {
  Mat3 m;
  m << 0.0, -v.z(), v.y(),  //
      v.z(), 0.0, -v.x(),   //
      -v.y(), v.x(), 0.0;
  return m;
}

/// det F = f0 . (f1 x f2) (columns of F).
inline double determinant(const Mat3& F) { return F.col(0).dot(F.col(1).cross(F.col(2))); }

/// cof(F) = dJ/dF = J F^{-T}, column by column: [f1 x f2, f2 x f0, f0 x f1] for
/// columns f0, f1, f2 of F. Defined (and smooth) for every F, singular or not.
inline Mat3 cofactor(const Mat3& F) {
  Mat3 C;
  C.col(0) = F.col(1).cross(F.col(2));
  C.col(1) = F.col(2).cross(F.col(0));
  C.col(2) = F.col(0).cross(F.col(1));
  return C;
}

/// Adds s * d^2 J / dF^2 to the 9x9 matrix H. From cof(F) column j = f_{j+1} x f_{j+2}
/// (indices mod 3): block (j, j+1) = -s [f_{j+2}]x, block (j, j+2) = s [f_{j+1}]x,
/// diagonal blocks zero. The result is symmetric (block (l, j) = block (j, l)^T).
inline void add_determinant_hessian(Mat9& H, const Mat3& F, double s) {
  for (int j = 0; j < 3; ++j) {
    const int j1 = (j + 1) % 3, j2 = (j + 2) % 3;
    H.block<3, 3>(3 * j, 3 * j1) -= s * cross_matrix(F.col(j2));
    H.block<3, 3>(3 * j, 3 * j2) += s * cross_matrix(F.col(j1));
  }
}

}  // namespace hofem::material_detail
