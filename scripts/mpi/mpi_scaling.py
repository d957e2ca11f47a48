#!/usr/bin/python3
"""Strong scaling of `hofem mms --distributed` over MPI ranks (scripts/bench-mpi).

    /usr/bin/python3 scripts/mpi/mpi_scaling.py OUT_DIR RANKS...

For each case (Neo-Hookean manufactured solution, P1-P3 tets) and rank count,
runs `mpirun -np K build/bin/hofem mms --distributed --json` three times and
keeps the median wall time (the machines are noisy), with each rank's figures
as the run reports them (`per_rank`: its piece of the mesh, ghosts, pattern and
matrix nonzeros, the doubles one matrix-vector product receives, AMG set-up and
Krylov seconds) and its peak resident memory (GNU time), plus the partition's
cut faces and imbalance from `hofem mesh --partition K --json`. A tiny run (the
baseline: MPI, hypre and the program with next to no mesh) separates fixed
memory from memory per unknown. The cube is generated piece by piece (no rank
builds it whole); what building it whole costs (the path of scenes and mesh
files) is measured by `hofem mesh` on the same cube. Writes OUT_DIR/scaling.json (measured values
only) and prints a table with speed-ups relative to the first rank count.
"""
import json
import statistics
import subprocess
import sys
import time
from pathlib import Path

CASES = [  # (order, cubes per side): ~1e4 - 1e5 unknowns
    (1, 24), (2, 14), (3, 9),
]
REPEATS = 3


def run(cmd):
    out = subprocess.run(cmd, check=True, capture_output=True, text=True).stdout
    return json.loads(out.strip().splitlines()[-1])


RSS_PREFIX = "/tmp/hofem_mpi_rss"


def run_with_rss(cmd):
    """The JSON result and each rank's peak resident memory in bytes (GNU time's %M, KiB,
    one file per rank: the ranks' stderr would interleave)."""
    for old in Path("/tmp").glob("hofem_mpi_rss.*"):
        old.unlink()
    p = subprocess.run(cmd, check=True, capture_output=True, text=True)
    rss = [int(f.read_text().split()[-1]) * 1024 for f in sorted(Path("/tmp").glob("hofem_mpi_rss.*"))]
    return json.loads(p.stdout.strip().splitlines()[-1]), rss


def mpirun(ranks, args):
    # One OpenMP thread per rank: this measures MPI scaling, not threads (2 cores here).
    command = " ".join(["build/bin/hofem", *args])
    return ["mpirun", "--allow-run-as-root", "--oversubscribe", "-x", "OMP_NUM_THREADS=1", "-np", str(ranks),
            "sh", "-c", f'exec /usr/bin/time -f "%M" -o {RSS_PREFIX}.$OMPI_COMM_WORLD_RANK {command}']


def mesh_peak(n, order):
    _, rss = run_with_rss(["sh", "-c", f'exec /usr/bin/time -f "%M" -o {RSS_PREFIX}.0 build/bin/hofem mesh '
                                       f'--box {n} --cell tet --order {order} --json'])
    return rss[0]


def measure_whole_mesh(rows):
    """The other input path (scenes, mesh files): every rank builds the whole mesh
    before keeping its piece. Its cost, measured directly: the peak memory of
    building the cube whole (`hofem mesh`, one process, no MPI), less that of a
    1-cell mesh (the program's own baseline)."""
    baseline = mesh_peak(1, 1)
    out = []
    for order, n in CASES:
        peak = mesh_peak(n, order)
        dofs = next(r["dofs"] for r in rows if r["order"] == order and r["n"] == n)
        out.append({"order": order, "n": n, "dofs": dofs, "peak_rss_bytes": peak})
        print(f"P{order} n={n}: building the whole mesh peaks at {peak / 2**20:.1f} MiB "
              f"(1-cell mesh: {baseline / 2**20:.1f} MiB)", flush=True)
    return {"whole_mesh_input": out, "whole_mesh_baseline_rss_bytes": baseline}


SOLVER_OPTIONS = [[], ["--krylov", "gmres"], ["--rigid-body-modes"], ["--amg", "amg-aggressive"]]


def measure_solver_options(ranks):
    """The distributed solver's options on `ranks` ranks, one run each (P2, P3 cases)."""
    out = []
    for order, n in CASES[1:]:
        for extra in SOLVER_OPTIONS:
            result, _ = run_with_rss(mpirun(ranks, ["mms", "--problem", "neohookean", "--order", str(order), "--n", str(n),
                                                    "--distributed", "--json", *extra]))
            r = result["per_rank"]
            row = {"order": order, "n": n, "ranks": ranks, "options": " ".join(extra) or "pcg + amg",
                   "newton_iterations": result["newton_iterations"], "l2_error": result["l2_error"],
                   "krylov_iterations_per_solve": r[0]["krylov_iterations"] / r[0]["krylov_solves"],
                   "amg_setup_seconds_per_setup": max(x["amg_setup_seconds"] / x["amg_setups"] for x in r),
                   "krylov_seconds": max(x["krylov_seconds"] for x in r), "total_seconds": result["total_seconds"]}
            out.append(row)
            print(f"P{order} n={n} {row['options']}: {row['krylov_iterations_per_solve']:.1f} its/solve, set-up "
                  f"{row['amg_setup_seconds_per_setup']:.3f} s, Krylov {row['krylov_seconds']:.2f} s, total "
                  f"{row['total_seconds']:.2f} s", flush=True)
    return out


def main():
    out_dir = Path(sys.argv[1] if len(sys.argv) > 1 else "reports/mpi")
    ranks = [int(r) for r in sys.argv[2:]] or [1, 2]
    out_dir.mkdir(parents=True, exist_ok=True)
    _, baseline_rss = run_with_rss(mpirun(1, ["mms", "--problem", "linear", "--order", "1", "--n", "1", "--distributed",
                                              "--json"]))
    print(f"baseline (1 cell, 1 rank): peak RSS {baseline_rss[0] / 2**20:.0f} MiB", flush=True)
    rows = []
    for order, n in CASES:
        for k in ranks:
            walls, result, rss = [], None, []
            for _ in range(REPEATS):
                t0 = time.perf_counter()
                result, rss = run_with_rss(mpirun(k, ["mms", "--problem", "neohookean", "--order", str(order), "--n",
                                                      str(n), "--distributed", "--json"]))
                walls.append(time.perf_counter() - t0)
            part = run(["build/bin/hofem", "mesh", "--box", str(n), "--cell", "tet", "--order", str(order),
                        "--partition", str(k), "--json"])["partition"]
            rows.append({
                "order": order, "n": n, "ranks": k, "dofs": result["dofs"],
                "wall_seconds_median": statistics.median(walls), "wall_seconds": walls,
                "solve_seconds": result["solve_seconds"], "assembly_seconds": result["assembly_seconds"],
                "setup_seconds": result["setup_seconds"], "newton_iterations": result["newton_iterations"],
                "l2_error": result["l2_error"],
                "ghost_nodes": part["ghost_nodes"], "halo_bytes_per_exchange": part["halo_bytes_per_exchange"],
                "cut_faces": part["cut_faces"], "imbalance": part["imbalance"],
                "peak_rss_bytes_per_rank": rss, "nodes": result["nodes"],
                "per_rank": result["per_rank"],
            })
            matvec = max(r["matvec_receive_bytes"] for r in result["per_rank"])
            print(f"P{order} n={n} ranks={k}: {rows[-1]['dofs']} DOFs, median {rows[-1]['wall_seconds_median']:.2f} s, "
                  f"Newton {result['newton_iterations']}, L2 {result['l2_error']:.6e}, "
                  f"peak RSS/rank {max(rss) / 2**20:.0f} MiB, matvec receives {matvec} B/rank", flush=True)
    whole_mesh = measure_whole_mesh(rows)
    solver_options = measure_solver_options(ranks[-1])
    base = {(r["order"], r["n"]): r["wall_seconds_median"] for r in rows if r["ranks"] == ranks[0]}
    for r in rows:
        r["speedup_vs_first"] = base[(r["order"], r["n"])] / r["wall_seconds_median"]
    (out_dir / "scaling.json").write_text(json.dumps({"cases": rows, "ranks": ranks, "repeats": REPEATS,
                                                      "baseline_rss_bytes": baseline_rss[0], **whole_mesh,
                                                      "solver_options": solver_options}, indent=1))
    print(f"\n{'case':<10}{'DOFs':>9}" + "".join(f"{'K=' + str(k) + ' s':>10}" for k in ranks) + f"{'speed-up':>10}")
    for order, n in CASES:
        sel = {r["ranks"]: r for r in rows if r["order"] == order and r["n"] == n}
        print(f"{'P' + str(order) + ' n=' + str(n):<10}{sel[ranks[0]]['dofs']:>9}"
              + "".join(f"{sel[k]['wall_seconds_median']:>10.2f}" for k in ranks)
              + f"{sel[ranks[-1]]['speedup_vs_first']:>10.2f}")
    print(f"\nmpi_scaling: wrote {out_dir / 'scaling.json'}")


if __name__ == "__main__":
    main()
