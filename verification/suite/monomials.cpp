#include "monomials.hpp"

namespace hofem::verification {

std::vector<Exponent> monomials_of_degree(int dim, int degree) {
  std::vector<Exponent> out;
  if (dim == 1) return {{degree, 0, 0}};
  for (int a = degree; a >= 0; --a) {
    if (dim == 2) {
      out.push_back({a, degree - a, 0});
      continue;
    }
    for (int b = degree - a; b >= 0; --b) out.push_back({a, b, degree - a - b});
  }
  return out;
}

namespace {
long double factorial(int n) {
  long double f = 1;
  for (int k = 2; k <= n; ++k) f *= k;
  return f;
}
}  // namespace

long double exact_monomial_integral(CellType cell, const Exponent& e) {
  const int d = dimension(cell);
  if (cell == CellType::Triangle || cell == CellType::Tetrahedron) {
    long double num = 1;
    int total = 0;
    for (int i = 0; i < d; ++i) {
      num *= factorial(e[i]);
      total += e[i];
    }
    return num / factorial(total + d);
  }
  long double v = 1;
  for (int i = 0; i < d; ++i) v *= (e[i] % 2 == 0) ? 2.0L / (e[i] + 1) : 0.0L;
  return v;
}

long double abs_monomial_integral(CellType cell, const Exponent& e) {
  if (cell == CellType::Triangle || cell == CellType::Tetrahedron) return exact_monomial_integral(cell, e);
  long double v = 1;
  for (int i = 0; i < dimension(cell); ++i) v *= 2.0L / (e[i] + 1);
  return v;
}

double monomial(const double* x, int dim, const Exponent& e) {
  double v = 1.0;
  for (int i = 0; i < dim; ++i)
    for (int k = 0; k < e[i]; ++k) v *= x[i];
  return v;
}

}  // namespace hofem::verification
