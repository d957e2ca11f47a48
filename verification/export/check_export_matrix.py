"""ctest mms.export_matrix: `hofem mms --export-matrix` writes the system it solved.

Runs a small linear case (P2 tets, n = 2, CHOLMOD), loads PREFIX.mtx,
PREFIX_rhs.mtx and PREFIX_solution.mtx with scipy.io.mmread (an independent
MatrixMarket reader) and checks that the matrix is the one a symmetric positive
definite elasticity system must be and that hofem's solution solves it.

usage: /usr/bin/python3 check_export_matrix.py HOFEM WORKDIR
"""
import json
import pathlib
import subprocess
import sys

import numpy as np
import scipy.io
import scipy.sparse.linalg

ORDER, N = 2, 2


def fail(message):
    sys.exit(f"mms.export_matrix: {message}")


def main(hofem, work):
    work = pathlib.Path(work)
    work.mkdir(parents=True, exist_ok=True)
    prefix = work / "mms_p2_n2"
    run = subprocess.run([hofem, "mms", "--problem", "linear", "--order", str(ORDER), "--n", str(N),
                          "--solver", "cholmod", "--json", "--export-matrix", str(prefix)],
                         capture_output=True, text=True, check=False)
    if run.returncode != 0:
        fail(f"hofem mms exited with {run.returncode}: {run.stderr}")
    reported = json.loads(run.stdout)["dofs"]
    K = scipy.io.mmread(f"{prefix}.mtx").tocsr()
    b = np.ravel(scipy.io.mmread(f"{prefix}_rhs.mtx"))
    u = np.ravel(scipy.io.mmread(f"{prefix}_solution.mtx"))

    # Unknowns: the interior nodes of a P2 mesh of n^3 cubes form a (2n - 1)^3
    # grid (the boundary is Dirichlet), 3 components each; hofem reports the same.
    expected = 3 * (ORDER * N - 1) ** 3
    if K.shape != (expected, expected) or reported != expected or b.size != expected or u.size != expected:
        fail(f"sizes K {K.shape}, b {b.size}, u {u.size}, reported {reported}; expected {expected}")

    # Symmetry: each entry is a sum of element contributions, symmetric up to the
    # order of the additions (a few ulps of the largest entry); %.17g reads back
    # exactly. 1e-12 relative is ~5000 ulps and still far below any real asymmetry.
    dense = K.toarray()
    asymmetry = np.abs(dense - dense.T).max() / np.abs(dense).max()
    if asymmetry > 1e-12:
        fail(f"K is not symmetric: max |K - K^T| / max |K| = {asymmetry:.3g}")
    # Positive definite (all Dirichlet, Poisson ratio 0.3): Cholesky must succeed.
    try:
        np.linalg.cholesky(dense)
    except np.linalg.LinAlgError:
        fail("K is not positive definite (numpy's Cholesky fails)")
    condition = np.linalg.cond(dense)

    # Solve with scipy (SuperLU, a different direct solver from hofem's CHOLMOD).
    x = scipy.sparse.linalg.spsolve(K.tocsc(), b)
    residual_scipy = np.linalg.norm(K @ x - b) / np.linalg.norm(b)
    residual_hofem = np.linalg.norm(K @ u - b) / np.linalg.norm(b)
    difference = np.linalg.norm(x - u) / np.linalg.norm(x)
    print(f"mms.export_matrix: {expected} unknowns, {K.nnz} nonzeros, asymmetry {asymmetry:.2g}, "
          f"cond(K) {condition:.3g}, residual scipy {residual_scipy:.2g} hofem {residual_hofem:.2g}, "
          f"|x_scipy - u_hofem| / |x_scipy| {difference:.2g}")
    # A backward-stable direct solve leaves a residual of a few eps * cond(K);
    # 1e-12 allows cond up to ~1e3 with margin.
    if residual_scipy > 1e-12:
        fail(f"scipy's solution leaves a relative residual {residual_scipy:.3g}")
    # hofem ran Newton to |g| <= 1e-10 of the force scale (newton_rtol in its JSON)
    # with a direct solve, so 1e-10 bounds its residual here; the two solutions then
    # differ by at most cond(K) times the sum of the residuals, cond(K) = 13 here
    # (printed): ~1.3e-9 < 1e-8. A wrong system or solution misses by O(1).
    if condition * 1e-10 > 1e-8:
        fail(f"cond(K) = {condition:.3g} is too large for the 1e-8 comparison's justification")
    if residual_hofem > 1e-10:
        fail(f"hofem's exported solution leaves a relative residual {residual_hofem:.3g} in the exported system")
    if difference > 1e-8:
        fail(f"hofem's and scipy's solutions differ by {difference:.3g} (relative)")


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2])
