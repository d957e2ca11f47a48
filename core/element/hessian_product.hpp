#pragma once
// The one dense product of an element Hessian, Hs = E Gt (element_kernel.hpp):
// E is rows x K (column-major, leading dimension a multiple of 8, padding rows
// zero), Gt is K x n (column-major, leading dimension ldg), Hs is rows x n (leading dimension that of E);
// K = 3 x quadrature points. For Tet20 with 24 points: 120 x 72 times 72 x 20.
//
// Eigen's general product spends most of its time packing at these sizes (its
// Tet20 element Hessian ran at ~5 GF/s, below the per-point 3x3 updates). With
// AVX-512 a register-blocked kernel instead: for 8 row vectors (64 rows) by 3
// columns of Hs, 24 accumulators stay in registers over the whole K loop, each
// E load feeds 3 FMAs. Without AVX-512, Eigen's product.
#include <Eigen/Core>

#if defined(__AVX512F__)
#include <immintrin.h>
#endif

namespace hofem {

#if defined(__AVX512F__)
namespace detail {

// Hs[:, j0 .. j0 + C) rows [8 r0, 8 (r0 + RV)) = E rows * Gt columns, K terms.
template <int RV, int C>
inline void hessian_product_tile(const double* E, int ld, int K, const double* Gt, int ldg, int j0, double* Hs, int r0) {
  __m512d acc[C][RV];
#pragma GCC unroll 8
  for (int c = 0; c < C; ++c)
#pragma GCC unroll 8
    for (int v = 0; v < RV; ++v) acc[c][v] = _mm512_setzero_pd();
  for (int k = 0; k < K; ++k) {
    const double* e = E + static_cast<std::ptrdiff_t>(k) * ld + 8 * r0;
    __m512d b[C];
#pragma GCC unroll 8
    for (int c = 0; c < C; ++c) b[c] = _mm512_set1_pd(Gt[static_cast<std::ptrdiff_t>(j0 + c) * ldg + k]);
#pragma GCC unroll 8
    for (int v = 0; v < RV; ++v) {
      const __m512d ev = _mm512_loadu_pd(e + 8 * v);
#pragma GCC unroll 8
      for (int c = 0; c < C; ++c) acc[c][v] = _mm512_fmadd_pd(ev, b[c], acc[c][v]);
    }
  }
#pragma GCC unroll 8
  for (int c = 0; c < C; ++c)
#pragma GCC unroll 8
    for (int v = 0; v < RV; ++v) _mm512_storeu_pd(Hs + static_cast<std::ptrdiff_t>(j0 + c) * ld + 8 * (r0 + v), acc[c][v]);
}

template <int RV>
inline void hessian_product_rows(const double* E, int ld, int K, const double* Gt, int ldg, int n, double* Hs, int r0) {
  int j = 0;
  for (; j + 3 <= n; j += 3) hessian_product_tile<RV, 3>(E, ld, K, Gt, ldg, j, Hs, r0);
  for (; j < n; ++j) hessian_product_tile<RV, 1>(E, ld, K, Gt, ldg, j, Hs, r0);
}

}  // namespace detail
#endif

/// Hs (ld x n) = E (ld x K) Gt (K x n, leading dimension ldg >= K); ld a multiple of 8 (the kernel reads whole
/// 8-row vectors: the padding rows of E must be finite, their results are ignored).
inline void hessian_product(const double* E, int ld, int K, const double* Gt, int ldg, int n, double* Hs) {
#if defined(__AVX512F__)
  const int vectors = ld / 8;
  int r = 0;
  for (; r + 8 <= vectors; r += 8) detail::hessian_product_rows<8>(E, ld, K, Gt, ldg, n, Hs, r);
  switch (vectors - r) {
    case 0: break;
    case 1: detail::hessian_product_rows<1>(E, ld, K, Gt, ldg, n, Hs, r); break;
    case 2: detail::hessian_product_rows<2>(E, ld, K, Gt, ldg, n, Hs, r); break;
    case 3: detail::hessian_product_rows<3>(E, ld, K, Gt, ldg, n, Hs, r); break;
    case 4: detail::hessian_product_rows<4>(E, ld, K, Gt, ldg, n, Hs, r); break;
    case 5: detail::hessian_product_rows<5>(E, ld, K, Gt, ldg, n, Hs, r); break;
    case 6: detail::hessian_product_rows<6>(E, ld, K, Gt, ldg, n, Hs, r); break;
    default: detail::hessian_product_rows<7>(E, ld, K, Gt, ldg, n, Hs, r); break;
  }
#else
  Eigen::Map<Eigen::MatrixXd>(Hs, ld, n).noalias() =
      Eigen::Map<const Eigen::MatrixXd>(E, ld, K) * Eigen::Map<const Eigen::MatrixXd, 0, Eigen::OuterStride<>>(Gt, K, n, Eigen::OuterStride<>(ldg));
#endif
}

}  // namespace hofem
