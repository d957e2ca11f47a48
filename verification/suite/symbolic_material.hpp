#pragma once
// The five material laws as sympy derives them from their strain energies
// (verification/symbolic/derive_material_laws.py, generated at build time):
// the reference that core/material's stresses and tangents are compared with,
// and from which the manufactured body forces of the MMS runs are computed.
// Nothing here calls core/material: the laws, the polar decomposition of the
// corotated model and the manufactured field's derivatives are all computed
// here, in long double (64-bit significand, ~11 bits beyond double), so the
// reference's own round-off stays below the double results it judges; the MMS
// body force in double (see mms_body_force).
#include <Eigen/Core>

#include <string>
#include <vector>

namespace hofem::verification {

/// A material law as its source writes it; `name` as core's material_names().
class SymbolicMaterial {
 public:
  /// mu, lambda: the Lamé parameters given to core's make_material (Stable
  /// Neo-Hookean re-parametrises them inside, as its source does).
  SymbolicMaterial(std::string name, double mu, double lambda);
  const std::string& name() const { return name_; }
  double energy(const Eigen::Matrix3d& F) const;
  Eigen::Matrix3d stress(const Eigen::Matrix3d& F) const;
  /// dP/dF in core's layout: A(i + 3 j, k + 3 l) = dP_ij / dF_kl. sympy's
  /// closed form, except for the corotated law (its R(F) has no closed form):
  /// there a five-point central difference of the symbolic P in long double
  /// (step 1e-4 relative: truncation <= ~1e-11, round-off ~1e-15 of |P|).
  Eigen::Matrix<double, 9, 9> tangent(const Eigen::Matrix3d& F) const;

  /// The body force that puts the MMS cube's manufactured displacement of scale
  /// s in equilibrium: f_i = -Div P = -sum_{j,k,l} dP_ij/dF_kl d^2u_k/dX_l dX_j,
  /// from this law's tangent and sympy's derivatives of the field; in double.
  Eigen::Vector3d mms_body_force(const Eigen::Vector3d& X, double s) const;

 private:
  std::string name_;
  long double mu_, lambda_;
};

/// The materials the generator derives (must equal core's material_names()).
std::vector<std::string> symbolic_material_names();

/// The rotation of F's polar decomposition F = R S in long double, by Higham's
/// scaled Newton iteration X <- (g X + X^-T / g) / 2 (Higham 1986, "Computing
/// the polar decomposition - with applications", SIAM J. Sci. Stat. Comput. 7).
/// For det F < 0 the iteration gives an orthogonal Q with det Q = -1; as the
/// inversion-safe corotated model takes it (Irving, Teran & Fedkiw 2004,
/// "Invertible finite elements for robust simulation of large deformation"),
/// R = Q (I - 2 v v^T) is then the nearest rotation, v the eigenvector of the
/// smallest eigenvalue of Q^T F, so S = R^T F has one negative eigenvalue.
Eigen::Matrix<long double, 3, 3> polar_rotation(const Eigen::Matrix<long double, 3, 3>& F);

}  // namespace hofem::verification
