#include "linalg/boomeramg_variants.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <array>
#include <stdexcept>

namespace hofem {

// Measured 2026-11-22 on the machine of shared/machine.md (AMD EPYC Zen 5, 2 vCPU),
// hypre 2.26, one MPI rank. Unit cube clamped at x = 0, linear material E = 1,
// nu = 0.3, unit body force; our CG (linalg/krylov.hpp) to ||b - A x|| <= 1e-8 ||b||
// from x = 0. Seconds are CPU time of the solving thread (the machine was shared,
// load 4-8: wall time was noise), best of 2-3 runs; they scatter by ~20 %.
//
//   system            N        variant          set-up s   CG its   solve s
//   P1 tet  n = 16    13,872   amg               0.096      17       0.093
//                              amg-nodal         0.135      20       0.119
//                              amg-aggressive    0.045      25       0.088
//                              hypre-pcg+amg     0.092      17       0.102
//   P2 tet  n = 8     13,872   amg               0.102      21       0.244
//                              amg-nodal         0.127      27       0.226
//                              amg-aggressive    0.052      33       0.220
//                              hypre-pcg+amg     0.121      21       0.222
//   Hex8    n = 16    13,872   amg               0.115      17       0.175
//                              amg-nodal         0.159      19       0.143
//                              amg-aggressive    0.047      22       0.139
//                              hypre-pcg+amg     0.087      17       0.119
//   P1 tet  n = 32   104,544   amg               0.995      19       1.967
//                              amg-nodal         1.179      22       1.976
//                              amg-aggressive    0.392      25       1.553
//                              hypre-pcg+amg     0.898      19       1.870
//   P2 tet  n = 16   104,544   amg               1.040      22       2.914
//                              amg-nodal         1.207      28       3.304
//                              amg-aggressive    0.448      34       2.798
//                              hypre-pcg+amg     0.946      22       2.987
//
// Why "amg" is the default (HYPRE_parcsr_ls.h for every parameter):
// - HMIS coarsening, extended+i interpolation truncated to 4 entries per row: hypre's
//   own defaults. PMIS (coarsen 8): 1-2 more iterations, 10-20 % cheaper cycles,
//   the same time within the scatter; Falgout (6): 1-2 fewer iterations, ~50 %
//   dearer cycles; classical (0) / extended (14) interpolation: 5-7 / 1 more
//   iterations; P_max 2: 5-7 more iterations.
// - Strength threshold 0.5, hypre's advice for 3D ("0.5 or 0.6"; "0.9 for
//   elasticity" did not help here: P2 n = 8 took 24 iterations at 0.9, 25 at 0.25,
//   21 at 0.5; 0.7 cuts the P1 set-up at n = 32 by 40 % but P2 n = 16 then takes
//   24 iterations instead of 22).
// - Smoother: l1 Gauss-Seidel forward on the way down (13), backward on the way up
//   (14), one sweep: the up sweep is the adjoint of the down sweep, so the V-cycle
//   is symmetric (test_mpi_hypre.cpp measures 3e-16) and CG-safe. Symmetric
//   Gauss-Seidel on both sides (8 or 6) saves 14-18 % of the iterations but doubles
//   the sweeps: P1 n = 32, 16 iterations in 2.62 s against 19 in 1.82 s. On one rank
//   l1 Gauss-Seidel is plain Gauss-Seidel; on many, the l1 term keeps the hybrid
//   (processor-block) sweep convergent (Baker, Falgout, Kolev, Yang 2011).
// - Systems AMG with unknown-based coarsening (NumFunctions 3) rather than nodal:
//   nodal coarsening (amg-nodal, row-sum block norm 4; Frobenius 1 was no better)
//   takes 3-6 more iterations; its cheaper cycle about evens the time out on P2
//   and does not on P1.
// - Standard rather than aggressive coarsening: aggressive coarsening on the first
//   level (amg-aggressive, multipass interpolation) sets up 2-2.5x faster and takes
//   18-34 % less time for set-up plus solve at nu = 0.3, but its iterations grow
//   fastest as the material stiffens: at nu = 0.45 (one run each), n = 32 P1 /
//   n = 16 P2 take 40 / 46 iterations against 24 / 27 for amg, and its time
//   advantage is gone (set-up + solve P1 3.45 s vs 3.29 s, P2 6.28 s vs 6.20 s).
//   amg-aggressive suits compressible materials and loose Newton tolerances. Two
//   aggressive levels: 32 / 45 iterations at nu = 0.3, faster for P1, slower for P2.
// - Rigid-body rotations as interpolation vectors (interp_vec_variant 2, GM-2, with
//   nodal coarsening, q_max 4) cut the iterations (n = 32 P1 22 -> 15, n = 16 P2
//   28 -> 18) but cost ~5 s of set-up and 2.4-3.3x the cycle: no named variant.
//   Variant 3, and q_max 2, made hypre's set-up fail on P1 n = 16 (reported by setup()).
// - hypre's PCG with the same V-cycle takes the same iterations as our CG and about
//   the same time: the cycle dominates either way.
// P3 (n = 10, 86,490 unknowns): 33 / 35 / 46 iterations for amg / nodal / aggressive.

namespace {

BoomerAmgOptions nodal_coarsening() {
  BoomerAmgOptions o;
  o.nodal = 4;  // row-sum norm of each node's 3x3 block
  return o;
}

BoomerAmgOptions aggressive_coarsening() {
  BoomerAmgOptions o;
  o.agg_num_levels = 1;  // multipass interpolation on that level (hypre's default)
  return o;
}

}  // namespace

// A function-local table: the benchmarks register their names (the solver
// registry, which reads this) during static initialisation, before a
// namespace-scope table with computed options would be initialised.
std::span<const BoomerAmgVariant> boomeramg_variants() {
  static const std::array<BoomerAmgVariant, 3> variants{{
      {"amg", "BoomerAMG V-cycle, systems AMG (3 functions), HMIS, extended+i, l1 Gauss-Seidel", BoomerAmgOptions{}},
      {"amg-nodal", "BoomerAMG with nodal coarsening (row-sum block norm)", nodal_coarsening()},
      {"amg-aggressive", "BoomerAMG with one level of aggressive coarsening (multipass interpolation)",
       aggressive_coarsening()},
  }};
  return variants;
}

std::vector<std::string> boomeramg_variant_names() {
  std::vector<std::string> names;
  for (const BoomerAmgVariant& v : boomeramg_variants()) names.emplace_back(v.name);
  return names;
}

BoomerAmgOptions boomeramg_options(std::string_view variant) {
  for (const BoomerAmgVariant& v : boomeramg_variants())
    if (v.name == variant) return v.options;
  throw std::invalid_argument(
      fmt::format("unknown BoomerAMG variant '{}' (valid: {})", variant, fmt::join(boomeramg_variant_names(), ", ")));
}

}  // namespace hofem
