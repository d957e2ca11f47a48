#pragma once
// How many threads OpenBLAS may use for the next call of a sparse direct solver.
//
// OpenBLAS (Debian's default build: its own pthread pool, not OpenMP's) keeps its
// worker threads spinning on sched_yield for 2^28 cycles (~0.1 s here) after
// every multithreaded BLAS call, waiting for more work. Between two
// factorisations hofem runs its own OpenMP loops (assembly, line search) on the
// same cores, and the spinning workers take their time: on this project's
// machine (2 cores, Linux 6.18), the finite-cell
// Hex20 twisting cylinder (1,425 unknowns, 389 CHOLMOD factorisations) spent
// 47.6 s in assembly instead of 13.2 s (perf: a third of the samples in
// sched_yield and libgomp's barrier). OpenBLAS's OpenMP build would share one
// pool, but measured slower here (CHOLMOD P2 n = 16: 11-14 s against 4.5 s).
//
// So a factorisation gets threads only when they pay: CHOLMOD on the
// manufactured cube, P2, 1 vs 2 BLAS threads (factorisation flops, seconds):
//   10,125 unknowns, 1.8e9 flops: 0.21 vs 0.21
//   20,577 unknowns, 7.6e9 flops: 0.59 vs 0.49
//   36,501 unknowns, 2.6e10 flops: 1.44 vs 1.25
//   89,373 unknowns, 1.6e11 flops: 6.2 vs 4.5
// Below kThreadedBlasMinFlops one thread (no pool wake-up, nothing left
// spinning), above it the pool (whose ~0.1 s of spinning is then small
// against the factorisation it sped up).

namespace hofem {

/// Factorisations of at least this many flops use OpenBLAS's threads.
inline constexpr double kThreadedBlasMinFlops = 1e10;

/// Sets OpenBLAS's thread count for a call of about `flops` floating-point
/// operations: 1 below kThreadedBlasMinFlops, else the pool's size at start-up
/// (OPENBLAS_NUM_THREADS) capped by OpenMP's (OMP_NUM_THREADS). Returns the count.
int use_blas_threads_for(double flops);

}  // namespace hofem
