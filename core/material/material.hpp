#pragma once
// Hyperelastic materials as pure functions of the deformation gradient F:
// energy density psi(F), first Piola–Kirchhoff stress P = dpsi/dF, and its
// derivative dP/dF as a 9x9 matrix.
//
// Flattening convention (used everywhere in hofem): vec(F) is column-major,
// vec(F)[i + 3 j] = F(i, j); dPdF(a, b) = d vec(P)[a] / d vec(F)[b].
#include <Eigen/Core>

#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace hofem {

using Mat3 = Eigen::Matrix3d;
using Mat9 = Eigen::Matrix<double, 9, 9>;

/// Lamé parameters.
struct LameParameters {
  double mu = 0.0;      ///< shear modulus
  double lambda = 0.0;  ///< first Lamé parameter
  /// mu = E / (2(1+nu)), lambda = E nu / ((1+nu)(1-2nu)); requires E > 0, -1 < nu < 0.5.
  static LameParameters from_young_poisson(double young, double poisson);
};

/// Thrown when stress or its derivative is requested where the material is not
/// defined (e.g. Neo-Hookean at det F <= 0); names the material and det F.
class MaterialDomainError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class Material {
 public:
  virtual ~Material() = default;
  /// The registry's name (material_registry.cpp; make_material sets it);
  /// empty for a material constructed directly.
  std::string_view name() const { return name_; }
  /// Whether psi is defined at F (false e.g. for Neo-Hookean with det F <= 0).
  virtual bool defined_at(const Mat3& F) const { (void)F; return true; }
  /// psi(F), plus P(F) into *P and dP/dF into *dPdF where those are non-null, from
  /// one evaluation that shares the work (one polar decomposition for corotated, one
  /// inverse for Neo-Hookean): the per-quadrature-point call of Newton's assembly,
  /// and the one function a material implements. Where the material is not
  /// defined, returns +infinity if only psi is requested and throws
  /// MaterialDomainError (naming the material and det F) if P or dP/dF is.
  virtual double evaluate(const Mat3& F, Mat3* P, Mat9* dPdF) const = 0;
  /// psi(F) alone; +infinity where the material is not defined (so a line search backs off).
  double energy(const Mat3& F) const { return evaluate(F, nullptr, nullptr); }
  /// P(F) alone; throws MaterialDomainError where not defined.
  Mat3 stress(const Mat3& F) const {
    Mat3 P;
    evaluate(F, &P, nullptr);
    return P;
  }
  /// dP/dF alone (9x9, see the flattening convention); throws MaterialDomainError where not defined.
  Mat9 stress_derivative(const Mat3& F) const {
    Mat9 dPdF;
    evaluate(F, nullptr, &dPdF);
    return dPdF;
  }
  /// Whether dP/dF is the same positive semi-definite matrix at every F (linear
  /// elasticity): the energy is then quadratic in the displacement, one linear
  /// solve is the static solution, and projecting dP/dF onto the PSD cone changes
  /// nothing (so assembly skips it).
  virtual bool constant_tangent() const { return false; }
  /// Whether the material needs a polar decomposition / SVD of F (corotated does).
  virtual bool needs_polar_decomposition() const { return false; }
  const LameParameters& lame() const { return lame_; }

 protected:
  explicit Material(LameParameters lame) : lame_(lame) {}
  LameParameters lame_;

 private:
  friend std::unique_ptr<Material> make_material(std::string_view name, LameParameters lame);
  std::string name_;
};

/// Polar decompositions (SVDs of F) the material computes over `assemblies`
/// evaluations of `elements` elements with `points` quadrature points each: one
/// per point and evaluation for a material that needs them (corotated), else 0.
long long polar_decompositions(const Material& material, long long assemblies, long long elements, long long points);

/// Names accepted by make_material, from the one table (material_registry.hpp).
std::vector<std::string> material_names();
/// Throws std::invalid_argument naming the valid choices for an unknown name.
std::unique_ptr<Material> make_material(std::string_view name, LameParameters lame);

/// Projection of a symmetric 9x9 matrix onto the positive semi-definite cone
/// (eigenvalues clamped at zero), used per quadrature point by Newton on request.
Mat9 project_psd(const Mat9& A);

}  // namespace hofem
