#!/usr/bin/env python3
"""Derive hofem's five material laws symbolically, independently of core/material.

Each strain energy psi(F) is written here as its source prints it; sympy
differentiates it into the first Piola-Kirchhoff stress P = dpsi/dF and, where
psi is a closed form in F, the tangent A = dP/dF (A[i][j][k][l] = dP_ij/dF_kl).
The result is a C++ header of templated functions (any scalar: double, long
double), written at build time (verification/CMakeLists.txt) and used by the
verification suite as the reference the code's own P and dP/dF are compared
with, and from which the manufactured body forces are computed.

Sources:
  linear     small-strain elasticity, psi = mu eps:eps + lambda/2 tr(eps)^2,
             eps = (F + F^T)/2 - I (the thesis, "High Order FEM Deformable Body
             Simulator", §2.2, as the limit its three materials share at F = I).
  stvk       the thesis §2.2 eq. (2.9): psi = mu |E|^2 + lambda/2 tr(E)^2,
             E = (F^T F - I)/2.
  corotated  the thesis §2.2 eq. (2.11): psi = mu |F - R|^2 + lambda/2 tr(S - I)^2
             with F = R S the polar decomposition. The thesis prints tr(S - I)
             without the square; its stress (2.12), P = 2 mu (F - R) +
             lambda tr(R^T F - I) R, is the derivative of the squared form, which
             is therefore used. R is an argument: because R^T F = S is symmetric,
             d psi / dR contracted with any admissible dR = R Omega (Omega skew)
             vanishes for both terms, so P is d psi/dF at fixed R (no dR/dF
             needed); the tangent needs dR/dF and is not generated (the suite
             differentiates P numerically in long double instead).
  neohookean the thesis §2.2 eq. (2.13): psi = mu/2 (I_1 - 3) - mu log J +
             lambda/2 log(J)^2, I_1 = tr(F^T F), J = det F.
  stable-neohookean  Smith, de Goes & Kim 2018, "Stable Neo-Hookean Flesh
             Simulation" (ACM TOG 37(2)): psi = mu'/2 (I_C - 3) + lambda'/2
             (J - alpha)^2 - mu'/2 log(I_C + 1), with the paper's Lamé
             re-parametrisation mu' = 4/3 mu, lambda' = lambda + 5/6 mu and
             alpha = 1 + 3 mu' / (4 lambda') (rest stability).

usage: derive_material_laws.py OUTPUT.hpp
"""
import sys

import sympy as sp
from sympy.printing.c import C99CodePrinter


def matrix(name):
    return sp.Matrix(3, 3, lambda i, j: sp.Symbol(f"{name}{i}{j}", real=True))


F, R = matrix("F"), matrix("R")
mu, lam = sp.symbols("mu lambda", positive=True)
I3 = sp.eye(3)


def frob(A, B):
    return sum(A[i, j] * B[i, j] for i in range(3) for j in range(3))


def energies():
    eps = (F + F.T) / 2 - I3
    E = (F.T * F - I3) / 2
    J = F.det()
    I1 = frob(F, F)
    mu_s, lam_s = sp.Rational(4, 3) * mu, lam + sp.Rational(5, 6) * mu
    alpha = 1 + sp.Rational(3, 4) * mu_s / lam_s
    return {
        "linear": mu * frob(eps, eps) + lam / 2 * eps.trace() ** 2,
        "stvk": mu * frob(E, E) + lam / 2 * E.trace() ** 2,
        "corotated": mu * frob(F - R, F - R) + lam / 2 * ((R.T * F).trace() - 3) ** 2,
        "neohookean": mu / 2 * (I1 - 3) - mu * sp.log(J) + lam / 2 * sp.log(J) ** 2,
        "stable_neohookean": mu_s / 2 * (I1 - 3) + lam_s / 2 * (J - alpha) ** 2 - mu_s / 2 * sp.log(I1 + 1),
    }


class Printer(C99CodePrinter):
    """C++ for any scalar type: integer powers as products, functions unqualified
    (the generated functions bring std::log into scope), no double literals
    forcing a type: rationals become T(p) / T(q)."""

    def _print_Pow(self, expr):
        b, e = expr.as_base_exp()
        if e.is_Integer and 1 < e <= 4:
            s = self.parenthesize(b, 100)
            return "*".join([s] * int(e))
        if e.is_Integer and e == -1:
            return f"(T(1) / {self.parenthesize(b, 100)})"
        if e == sp.Rational(1, 2):
            return f"sqrt({self._print(b)})"
        return f"pow({self._print(b)}, {self._print(e)})"

    def _print_Rational(self, expr):
        return f"(T({expr.p}) / T({expr.q}))"

    def _print_Integer(self, expr):
        return f"T({expr.p})"

    def _print_Pi(self, expr):
        return "T(3.141592653589793238462643383279502884L)"

    def _print_Exp1(self, expr):
        return "exp(T(1))"

    def _print_Float(self, expr):
        return f"T({expr})"

    def _print_Symbol(self, expr):
        n = expr.name
        if len(n) == 2 and n[0] == "x" and n[1].isdigit():
            return f"X[{n[1]}]"
        if len(n) == 3 and n[0] in "FR" and n[1:].isdigit():
            return f"{n[0]}[{3 * int(n[1]) + int(n[2])}]"
        return n


def emit(name, outputs, args):
    """One templated function: `outputs` is a list of (array name, [expr...])."""
    flat = [e for _, es in outputs for e in es]
    reps, reduced = sp.cse(flat, symbols=sp.numbered_symbols("t"), optimizations="basic")
    p = Printer()
    lines = [f"template <class T>", f"void {name}({args}) {{",
             "  using std::log; using std::sqrt; using std::pow; using std::sin; using std::cos; using std::exp;"]
    for sym, expr in reps:
        lines.append(f"  const T {sym} = {p.doprint(expr)};")
    k = 0
    for out, es in outputs:
        for i in range(len(es)):
            lines.append(f"  {out}[{i}] = {p.doprint(reduced[k])};")
            k += 1
    lines.append("}")
    return "\n".join(lines)


def manufactured_displacement():
    """The manufactured displacement of hofem's MMS cube (core/study/
    manufactured_solution.hpp states it; written out again here so that its
    derivatives are sympy's, not the code's): value, gradient G[3 i + j] =
    du_i/dX_j and Hessians H[9 k + 3 l + j] = d^2 u_k / dX_l dX_j, for scale s."""
    X = sp.symbols("x0 x1 x2", real=True)
    s, q = sp.Symbol("s", real=True), sp.Rational(1, 4)
    x, y, z = X
    u = [s * sp.sin(sp.pi * x) * sp.sin(sp.pi * y) * sp.sin(sp.pi * z),
         s * sp.Rational(1, 2) * sp.sin(sp.pi * (x + q)) * sp.sin(sp.pi * (y + q)) * sp.sin(sp.pi * (z + q)),
         s * q * sp.cos(sp.pi * x) * sp.cos(sp.pi * y) * sp.exp(z)]
    G = [sp.diff(u[i], X[j]) for i in range(3) for j in range(3)]
    H = [sp.diff(u[k], X[l], X[j]) for k in range(3) for l in range(3) for j in range(3)]
    return emit("manufactured_displacement", [("u", u), ("G", G), ("H", H)], "const T* X, T s, T* u, T* G, T* H")


def main(path):
    parts = [manufactured_displacement()]
    for material, psi in energies().items():
        P = [sp.diff(psi, F[i, j]) for i in range(3) for j in range(3)]
        uses_r = material == "corotated"
        args = "const T* F, " + ("const T* R, " if uses_r else "") + "T mu, T lambda"
        parts.append(f"// {material}: psi and P = dpsi/dF (P row-major, P[3 i + j] = P_ij).")
        parts.append(emit(f"{material}_energy_stress", [("psi", [psi]), ("P", P)], args + ", T* psi, T* P"))
        if not uses_r:
            # A[9 (3 i + j) + 3 k + l] = dP_ij / dF_kl
            A = [sp.diff(Pij, F[k, l]) for Pij in P for k in range(3) for l in range(3)]
            parts.append(f"// {material}: the tangent A[9 (3 i + j) + 3 k + l] = dP_ij / dF_kl.")
            parts.append(emit(f"{material}_tangent", [("A", A)], args + ", T* A"))
    header = ["// Generated by verification/symbolic/derive_material_laws.py (sympy " + sp.__version__ + ")",
              "// at build time; do not edit. The energies and their sources are in that script.",
              "#pragma once", "#include <cmath>", "", "namespace hofem::verification::symbolic {", ""]
    with open(path, "w") as f:
        f.write("\n".join(header + ["\n\n".join(parts), "", "}  // namespace hofem::verification::symbolic", ""]))


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit("usage: derive_material_laws.py OUTPUT.hpp")
    main(sys.argv[1])
