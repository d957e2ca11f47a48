#include "material/neo_hookean.hpp"

#include "material/tensor_ops.hpp"

#include <fmt/format.h>

#include <cmath>
#include <limits>

namespace hofem {

// The same determinant (f0 . (f1 x f2), as in evaluate) everywhere, so defined_at,
// energy and stress agree on the domain boundary to the last bit.
bool NeoHookean::defined_at(const Mat3& F) const { return material_detail::determinant(F) > 0.0; }

double NeoHookean::evaluate(const Mat3& F, Mat3* P, Mat9* dPdF) const {
  const Mat3 C = material_detail::cofactor(F);
  const double J = F.col(0).dot(C.col(0));  // = determinant(F)
  if (!(J > 0.0)) {  // also NaN
    if (P || dPdF)
      throw MaterialDomainError(fmt::format("neohookean: not defined at det F = {:.6g} (requires det F > 0)", J));
    return std::numeric_limits<double>::infinity();
  }
  const double logJ = std::log(J);
  if (P || dPdF) {
    const Mat3 G = C / J;  // F^{-T}
    if (P) *P = lame_.mu * F + (lame_.lambda * logJ - lame_.mu) * G;
    if (dPdF) {
      const auto g = material_detail::vec(G);
      Mat9& H = *dPdF;
      H = lame_.lambda * g * g.transpose();
      H.diagonal().array() += lame_.mu;
      // (mu - lambda log J) G_il G_kj: block (j, l), indices (i, k), is g_l g_j^T (g_j = column j of G).
      const double c = lame_.mu - lame_.lambda * logJ;
      for (int l = 0; l < 3; ++l)
        for (int j = 0; j < 3; ++j) H.block<3, 3>(3 * j, 3 * l) += c * G.col(l) * G.col(j).transpose();
    }
  }
  return 0.5 * lame_.mu * (F.squaredNorm() - 3.0) - lame_.mu * logJ + 0.5 * lame_.lambda * logJ * logJ;
}

}  // namespace hofem
