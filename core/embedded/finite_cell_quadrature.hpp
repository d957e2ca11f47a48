#pragma once
// Finite-cell quadrature (Longva et al. 2020 §4.4-4.5, §5.3): for every cell of a
// background mesh, rules over the part of the embedded geometry inside it, in
// the cell's reference coordinates, ready for the Assembler (ElementRules, embedded/element_rules.hpp).
//
// Background cells must be affine: Tet4, straight-sided Tet10 (and higher), and
// parallelepiped Hex8/Hex20 (box grids, sheared or rotated). Their map
// X = X0 + A xi is then exact, the cell is the intersection of the half-spaces
// that pull back the reference cell's faces (xi_k >= 0, sum xi <= 1 on the tet,
// |xi_k| <= 1 on the hex), and the map back to reference coordinates is A^-1
// (the Newton inverse of §4.5 is needed only for curved cells, which are refused
// with the element's index rather than integrated wrongly).
//
// Two rules per cell, as Longva et al. 2020 do (§6 "Setup"):
//  - stiffness: strength m, simplified by the LP of §4.4 to at most C(m+3, 3)
//    positive-weight points chosen among the clipped rule's points. Default: the
//    degree that integrates the linear-elastic integrand grad N_i . grad N_j of an
//    affine cell exactly - 2(p-1) on tets, raised to 2p as our standard Tet10
//    assembly does for nonlinear materials; 2 (d-1) on hexes, d the basis' highest
//    total degree: 4 for Hex8, 6 for Hex20. Longva et al. 2020 use 2 for Hex8, 4 for Hex20
//    and 3 for Tet10 (§6), which under-integrates the stiffness of cut hexes
//    (total-degree rules cannot use the tensor structure of Gauss rules): we
//    prefer exactness at the price of 35 instead of 10 (Hex8) and 84 instead of
//    35 (Hex20) points per cut cell;
//  - mass and body loads: a higher strength (default 2 x the basis' highest total
//    degree: exact for N_i N_j on an affine cell). Longva et al. 2020 (§6 "Setup")
//    do not simplify it ("only needed once"); by default neither do we. With
//    fit_mass (the scenes' choice) it is replaced by a moment-fitted rule of
//    C(m+3, 3) points (fit_quadrature): we differ from the paper because the raw
//    rule is what dominated the set-up's memory and much of its time - every
//    point is tabulated with the basis' values and gradients (84 doubles for
//    Hex20), and the Hex20 twisting cylinder on a 12 x 12 x 18 grid had 4.5 M mass
//    points (3.8 GB peak, tabulated twice with the stabilisation). The fitted rule
//    integrates every polynomial of degree <= m as the clipped rule does, and
//    N_i N_j is such a polynomial on an affine cell (Longva et al. 2020 §4.4: the
//    moments are all a rule must keep), so the consistent mass matrix, the lumped
//    masses taken from it and constant body loads are those of the clipped rule to
//    rounding. Unlike the LP (§4.4) it may have negative weights and points outside the
//    geometry (inside the bounding box of its cut part), so a non-polynomial load
//    is integrated less faithfully; scenes have constant gravity only.
// Uncut cells (volume fraction 1) keep the standard rules (null entries).
#include "basis/basis_tabulation.hpp"
#include "embedded/element_rules.hpp"
#include "embedded/quadrature_simplification.hpp"
#include "embedded/tet_clipping.hpp"
#include "mesh/mesh.hpp"

#include <Eigen/Core>

#include <memory>
#include <span>
#include <vector>

namespace hofem {

struct FiniteCellOptions {
  int stiffness_degree = -1;    ///< < 0: tet 2p, hex 2 (d - 1) (Hex8 4, Hex20 6), see above
  int mass_degree = -1;         ///< < 0: 2 x highest total degree of the basis (Tet p, Hex8 3, Hex20 4)
  bool simplify = true;         ///< LP simplification (§4.4) of the stiffness rules
  /// Moment fitting of the mass rules (fit_quadrature) to C(m+3, 3) points, m the
  /// mass degree: the same mass matrix to rounding (see the header comment).
  bool fit_mass = false;
  /// Options of the stiffness rules' LP (fast = false: the reference path, tests).
  SimplificationOptions simplification{};
  /// Uncut cells get null rules (the Assembler's standard rules). false keeps
  /// their clipped rules (tests that compare the two).
  bool standard_rule_inside = true;
};

/// The affine map of a background cell, X = origin + A xi.
struct AffineCell {
  Eigen::Vector3d origin;
  Eigen::Matrix3d A;
  Eigen::Matrix3d A_inverse;
  Eigen::Vector3d reference(const Eigen::Vector3d& X) const { return A_inverse * (X - origin); }
};
/// The least-squares affine fit of a cell's nodes; for a curved cell (affine
/// false) a starting guess of the inverse map.
struct AffineFit {
  AffineCell map;            ///< A_inverse set unless degenerate
  double misfit = 0.0;       ///< largest node distance from the fitted map
  double size = 0.0;         ///< the nodes' bounding-box diagonal
  bool affine = false;       ///< misfit <= 1e-10 size
  bool degenerate = false;   ///< |det A| <= 1e-12 size^3
};
AffineFit fit_affine_cell(const Mesh& mesh, int element);
/// Throws std::invalid_argument naming the element if its nodes are not an
/// affine image of the reference element (to 1e-10 of its size) or A is singular.
AffineCell affine_cell(const Mesh& mesh, int element);
/// The half-spaces whose intersection is the cell (4 for a tet, 6 for a hex).
std::vector<HalfSpace> cell_half_spaces(CellType cell, const AffineCell& map);

struct CellQuadrature {
  /// Per element: stiffness rule (null: the standard rule of an uncut cell;
  /// empty: the geometry misses the cell or the cell was dropped).
  std::vector<std::shared_ptr<const ElementQuadrature>> rules;
  /// Per element: mass / load rule, same conventions.
  std::vector<std::shared_ptr<const ElementQuadrature>> mass_rules;
  /// Per element: volume of (geometry ∩ cell) / volume of the cell.
  std::vector<double> volume_fraction;
  /// Per element: stiffness points before and after simplification (0 for uncut and empty cells).
  std::vector<int> points_before, points_after;
  /// Per element: the LP simplification's relative moment residual (0 where not simplified).
  std::vector<double> moment_residual;
  long long points = 0;             ///< stiffness points before simplification, summed over cut cells
  long long simplified_points = 0;  ///< ... after
  long long mass_points = 0;        ///< mass points over cut cells (after fitting, if fit_mass)
  long long mass_points_clipped = 0;  ///< mass points of the clipped rules over cut cells
  double max_mass_moment_residual = 0.0;  ///< fit_mass: largest relative moment residual of a fitted rule
  double max_mass_weight_ratio = 0.0;     ///< fit_mass: largest sum |w| / sum w of a fitted rule
  int mass_fit_failures = 0;              ///< fit_mass: cells whose fit missed 1e-11 (clipped rule kept)
  int simplification_failures = 0;  ///< cells whose LP failed (their clipped rule is kept)
  double max_moment_residual = 0.0;
  double generation_seconds = 0.0;      ///< clipping and mapping, summed over threads
  double simplification_seconds = 0.0;  ///< the LPs, summed over threads
  double wall_seconds = 0.0;            ///< the whole call
  int stiffness_degree = 0, mass_degree = 0;

  ElementRules element_rules() const { return {rules, mass_rules}; }
};

CellQuadrature finite_cell_quadrature(const Mesh& background, std::span<const Tetrahedron> geometry,
                                      const FiniteCellOptions& options = {});
/// Stiffness and mass rules of one strength, clipped rules kept everywhere, no
/// simplification (the raw §4.5 rules).
CellQuadrature finite_cell_quadrature(const Mesh& background, std::span<const Tetrahedron> geometry, int degree);

/// Per background cell, the volume fraction finite_cell_quadrature(background,
/// geometry, options) reports (the same clipped rule of the stiffness degree,
/// summed in the same order: equal to the last bit), without making any rule.
/// What a finished run's measurement needs to know which cells are active, where
/// the rules' tabulation may not fit: the unsimplified Hex20 cylinder of Longva et
/// al. 2020 §6.3 at the seed's size has 32.5 M stiffness points, ~21 GB tabulated.
std::vector<double> finite_cell_volume_fractions(const Mesh& background, std::span<const Tetrahedron> geometry,
                                                 const FiniteCellOptions& options = {});
/// Volume of the reference cell: 1/6 (tetrahedron), 8 ([-1, 1]^3).
double reference_cell_volume(CellType cell);
/// A cut cell: 0 < f < 1, the volume fraction's 1 taken up to the clipped rule's rounding.
bool finite_cell_cut(double volume_fraction);
/// Longva et al. 2020 §5.3: a cut cell (0 < f < 1) whose volume fraction f is
/// below drop_fraction is dropped (stabilise_finite_cells, finite_cell_active).
bool finite_cell_dropped(double volume_fraction, double drop_fraction);
/// Per cell: it integrates something after stabilise_finite_cells with this
/// drop_fraction (uncut, or cut and kept); false where the geometry misses it or
/// it was dropped. The one definition of "active" (SceneEmbedding, the study's measurements).
std::vector<char> finite_cell_active(const std::vector<double>& volume_fraction, double drop_fraction);

/// Longva et al. 2020 §5.3, applied to the rules of finite_cell_quadrature:
///  - cells whose volume fraction is positive but below drop_fraction are
///    dropped (their rules emptied; listed in `dropped`): a sliver's stiffness is
///    too small to control its DOFs (its embedded points are extrapolated from the
///    nearest kept cell, embedded_points.hpp);
///  - every other cut cell (fraction < 1) gets the standard Gauss points of the
///    full cell with weights scaled by `stabilisation`, in its stiffness and its
///    mass rule, so that both stay positive definite however small the cut part
///    is (the fictitious-domain stiffness of the finite cell method).
struct FiniteCellStabilisation {
  double drop_fraction = 1e-4;
  double stabilisation = 1e-6;
  int gauss_degree = -1;  ///< of the added points; < 0: 2 p (the standard stiffness rule)
  /// Also stabilise the mass rules (dynamics: the mass matrix must stay positive
  /// definite). A static problem uses its mass rules only for loads, which must
  /// not carry a fictitious part; false leaves them as they are (and saves
  /// re-tabulating the largest rules: 1e7 points on the Fig. 10 Hex20 h = 1/32 grid).
  bool mass = true;
  /// >= 0: the stabilised stiffness rule (cut points plus scaled Gauss points) is
  /// simplified again by the LP of §4.4 to this strength, so a cut cell keeps at
  /// most C(m+3, 3) points instead of that plus the full cell's rule (Tet10:
  /// 35 instead of 35 + 14). The original weights are a feasible point of the
  /// LP, so it has a solution; the folded rule integrates the stabilised
  /// integrand - the cut part plus `stabilisation` times the full cell - exactly
  /// to degree m, which covers the linear-elastic stiffness grad N_i . grad N_j
  /// of an affine cell (degree 2(p-1) <= m): that stiffness, and the lower bound
  /// on its eigenvalues that the stabilisation exists for, are unchanged. Longva
  /// et al. 2020 §5.3 add the Gauss points beside the simplified rule and do not
  /// say whether they fold them; the fold is ours (measured in the slingshot
  /// study: assembly is most of a finite-cell step). A cell whose
  /// LP fails keeps the unfolded rule. < 0: no fold.
  int simplify_degree = -1;
  /// Options of that fold's LP (fast = false: the reference path, tests).
  SimplificationOptions simplification{};
};
struct StabilisedCells {
  std::vector<int> dropped;     ///< elements dropped for a volume fraction below drop_fraction
  std::vector<int> stabilised;  ///< cut elements that received the scaled Gauss points
  int folded = 0;               ///< stabilised stiffness rules simplified again (simplify_degree >= 0)
  double simplification_seconds = 0.0;  ///< those LPs, summed over threads
};
StabilisedCells stabilise_finite_cells(const Mesh& background, CellQuadrature& cells,
                                       const FiniteCellStabilisation& options = {});

/// The cells the Additive-Schwarz preconditioner treats with blocks (Longva et al. 2020
/// §5.2): cut cells (0 < fraction < 1, not dropped) with a volume fraction below
/// `threshold` (Longva et al. 2020: 0.5-0.7 work well; 0.5 in its §6.5). Ascending.
std::vector<int> schwarz_block_elements(const CellQuadrature& cells, double threshold = 0.5);


}  // namespace hofem
