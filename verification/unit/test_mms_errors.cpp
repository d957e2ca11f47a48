// mms_errors against closed forms: with u = 0 the "errors" are the norms of u*
// itself, integrable by hand (the manufactured field is a product of sines,
// cosines and e^z on the unit cube).
#include "mesh/box_mesh.hpp"
#include "study/manufactured_solution.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace hofem {
namespace {

// ||u*||^2 and |u*|_1^2 over [0, 1]^3 for scale 1 (manufactured_solution.cpp's
// u* = (sx sy sz, 0.5 Sx Sy Sz, 0.25 cx cy e^z), S the sines shifted by 1/4):
// every sin^2 and cos^2 factor over a whole period integrates to 1/2, e^(2z) to
// (e^2 - 1) / 2, so
//   ||u*||^2  = 1/8 + 1/32 + (e^2 - 1) / 128,
//   |u*|_1^2 = 3 pi^2 / 8 + 3 pi^2 / 32 + (2 pi^2 + 1)(e^2 - 1) / 128.
double l2_squared() { return 1.0 / 8 + 1.0 / 32 + (std::exp(2.0) - 1.0) / 128; }
double h1_squared() {
  const double pi2 = M_PI * M_PI;
  return 3 * pi2 / 8 + 3 * pi2 / 32 + (2 * pi2 + 1) * (std::exp(2.0) - 1.0) / 128;
}

// The error rule (degree >= p + 3) integrates these smooth integrands with an
// error of O(h^(degree + 1)): measured on n = 4, 3.9e-10 relative (orders 1, 2:
// degree 4 and 5) and 3.1e-13 (order 3, degree 6). 1e-8 leaves 25x over the
// largest; a rule of degree p (under-integrated) misses by 1.3e-3, 1.9e-6 and
// 4.5e-7 in L2 (3.4e-7 in H1; measured), 34x or more over the bound.
TEST(MmsErrors, NormsOfTheManufacturedFieldInClosedForm) {
  const ManufacturedDisplacement ustar{};
  for (int order : {1, 2, 3}) {
    const Mesh mesh = box_mesh(unit_cube(4), CellType::Tetrahedron, order);
    const MmsErrors e = mms_errors(mesh, ustar, Eigen::VectorXd::Zero(3 * mesh.num_nodes()));
    EXPECT_GE(e.degree, order + 3);
    const double l2 = std::fabs(e.l2 * e.l2 / l2_squared() - 1), h1 = std::fabs(e.h1 * e.h1 / h1_squared() - 1);
    EXPECT_LE(l2, 1e-8) << "order " << order << ", rule degree " << e.degree;
    EXPECT_LE(h1, 1e-8) << "order " << order << ", rule degree " << e.degree;
  }
}

}  // namespace
}  // namespace hofem
