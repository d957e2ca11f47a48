#!/usr/bin/python3
"""A sizing model for distributed runs past this machine (issue 7), from the
1- and 2-rank measurements of scripts/bench-mpi (reports/mpi/scaling.json).

    /usr/bin/python3 scripts/mpi_model.py [reports/mpi]

Writes reports/mpi/model.md and model.json: per-rank memory, halo volume and
linear-solve time against rank count for P1-P3 up to 1e9 unknowns. Every number
is labelled measured (from scaling.json), derived (arithmetic on measured
numbers) or extrapolated (a stated assumption carried to sizes not run).
"""
import json
import math
import sys
from pathlib import Path

NODE_MEMORY = 20 * 2**30       # usable bytes of a 24 GiB node like this one (assumption: 4 GiB for the OS)
RANKS_PER_NODE = 2             # one rank per core, as measured here
NET_BANDWIDTH = 10e9           # bytes/s between nodes (assumption: a 100 Gb/s class interconnect)
NET_LATENCY = 2e-6             # s per message (assumption)
AMG_LEVELS_MESSAGES = 30       # halo messages per V-cycle: ~10 levels x (smoother + residual + prolongation)
ITERATION_GROWTH = 1.10        # AMG-PCG iterations x1.10 per 8x unknowns (measured in issue 4: P2 19 -> 21 over 350x)
SIZES = [1e6, 1e7, 1e8, 1e9]


def per_order(cases):
    out = {}
    for order in sorted({c["order"] for c in cases}):
        one = next(c for c in cases if c["order"] == order and c["ranks"] == 1)
        two = next(c for c in cases if c["order"] == order and c["ranks"] == 2)
        n = one["dofs"]
        m1 = max(one["peak_rss_bytes_per_rank"])
        m2 = max(two["peak_rss_bytes_per_rank"])
        solves = one["newton_iterations"] + 1  # Newton steps plus the tangent predictor
        nodes = one["nodes"]
        ghosts_one_plane = max(two["ghost_nodes"])
        out[order] = {
            "measured": {"dofs": n, "nodes": nodes, "rss_1_rank": m1, "rss_2_ranks": m2,
                         "solve_seconds_1_rank": one["solve_seconds"], "solve_seconds_2_ranks": two["solve_seconds"],
                         "linear_solves": solves, "ghost_nodes_2_ranks": ghosts_one_plane,
                         "speedup_2_ranks": one["wall_seconds_median"] / two["wall_seconds_median"]},
            "derived": {
                # M(K) = R + D / K through the two measurements.
                "replicated_bytes_per_dof": (2 * m2 - m1) / n,
                "distributed_bytes_per_dof": 2 * (m1 - m2) / n,
                "seconds_per_dof_per_solve": one["solve_seconds"] / solves / n,
                # One cut plane of a cube of `nodes` nodes: ghosts = c nodes^(2/3).
                "plane_ghost_coefficient": ghosts_one_plane / nodes ** (2 / 3),
                "nodes_per_dof": nodes / n,
            },
        }
    return out


def project(model, order, dofs):
    d = model[order]["derived"]
    r, dd = d["replicated_bytes_per_dof"], d["distributed_bytes_per_dof"]
    total = r + dd
    # Target design (mesh, pattern and vectors distributed too): all bytes scale with N / K.
    nodes_needed = max(1, math.ceil(dofs * total / NODE_MEMORY))  # whole nodes, their memory filled
    ranks = nodes_needed * RANKS_PER_NODE
    dofs_per_rank = dofs / ranks
    nodes_per_rank = dofs_per_rank * d["nodes_per_dof"]
    # Cubic RCB parts: 3 of a part's 6 faces are owned by lower-numbered neighbours.
    ghosts = 3 * d["plane_ghost_coefficient"] * nodes_per_rank ** (2 / 3)
    halo = ghosts * 3 * 8
    growth = ITERATION_GROWTH ** (math.log(dofs / model[order]["measured"]["dofs"]) / math.log(8))
    compute = d["seconds_per_dof_per_solve"] * dofs_per_rank * growth
    # Per solve: iterations ~ (measured ~20) x growth, each with a halo exchange per level.
    iterations = 20 * growth
    comm = iterations * AMG_LEVELS_MESSAGES * (NET_LATENCY + halo / NET_BANDWIDTH)
    return {
        "dofs": dofs, "ranks": ranks, "nodes_of_24GiB": ranks // RANKS_PER_NODE,
        "memory_per_rank_target": total * dofs_per_rank,
        "memory_per_rank_current": r * dofs + dd * dofs_per_rank,
        "ghost_nodes_per_rank": ghosts, "halo_bytes_per_exchange": halo,
        "seconds_per_solve_compute": compute, "seconds_per_solve_communication": comm,
    }


def gib(b):
    return f"{b / 2**30:.2f} GiB" if b >= 2**30 else f"{b / 2**20:.0f} MiB"


def main():
    out_dir = Path(sys.argv[1] if len(sys.argv) > 1 else "reports/mpi")
    cases = json.loads((out_dir / "scaling.json").read_text())["cases"]
    model = per_order(cases)
    projections = {o: [project(model, o, n) for n in SIZES] for o in model}
    (out_dir / "model.json").write_text(json.dumps({"model": model, "projections": projections,
                                                    "assumptions": {"node_memory": NODE_MEMORY,
                                                                    "ranks_per_node": RANKS_PER_NODE,
                                                                    "net_bandwidth": NET_BANDWIDTH,
                                                                    "net_latency": NET_LATENCY,
                                                                    "iteration_growth_per_8x": ITERATION_GROWTH}},
                                                   indent=1))
    lines = ["# Sizing distributed runs (issue 7)", "",
             "Made by `scripts/mpi_model.py` from `reports/mpi/scaling.json` (`scripts/bench-mpi`: the Neo-Hookean",
             "manufactured solution on 1 and 2 ranks of this 2-core, 24 GiB machine, one thread per rank).", "",
             "## Measured (per order)", "",
             "| order | DOFs | peak RSS / rank, 1 rank | 2 ranks | linear solves | solve s, 1 rank | 2 ranks | speed-up (whole run) | ghost nodes, 2 ranks |",
             "|---|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for o, m in model.items():
        x = m["measured"]
        lines.append(f"| P{o} | {x['dofs']:,} | {gib(x['rss_1_rank'])} | {gib(x['rss_2_ranks'])} | {x['linear_solves']} | "
                     f"{x['solve_seconds_1_rank']:.2f} | {x['solve_seconds_2_ranks']:.2f} | {x['speedup_2_ranks']:.2f} | "
                     f"{x['ghost_nodes_2_ranks']} |")
    lines += ["", "## Derived (arithmetic on the measurements)", "",
              "Memory per rank through the two runs as M(K) = R + D/K: R is what every rank holds whatever K is",
              "(today: the whole mesh, the sparsity pattern, full-length vectors), D what is split (hypre's",
              "matrix and AMG hierarchy, this rank's element work).", "",
              "| order | replicated R, bytes/DOF | distributed D, bytes/DOF | solve s per DOF per solve | ghosts = c nodes^(2/3), c |",
              "|---|---:|---:|---:|---:|"]
    for o, m in model.items():
        d = m["derived"]
        lines.append(f"| P{o} | {d['replicated_bytes_per_dof']:.0f} | {d['distributed_bytes_per_dof']:.0f} | "
                     f"{d['seconds_per_dof_per_solve']:.2e} | {d['plane_ghost_coefficient']:.2f} |")
    lines += ["", "## Extrapolated", "",
              "Assumptions (not measured): 20 GiB usable per 24 GiB node, 2 ranks per node; the target design where",
              "mesh, pattern and vectors are distributed too, so that all of R + D scales with N/K; cubic RCB parts",
              "with ghosts on 3 faces; AMG-PCG iterations growing x1.10 per 8x unknowns (issue 4's measured AMG",
              f"scaling) from ~20; {AMG_LEVELS_MESSAGES} halo messages per V-cycle at {NET_LATENCY * 1e6:.0f} us and "
              f"{NET_BANDWIDTH / 1e9:.0f} GB/s.", "",
              "| order | DOFs | ranks (nodes) | memory / rank, target | memory / rank, today's replicated design | ghost nodes / rank | halo / exchange | solve s: compute + comm |",
              "|---|---:|---:|---:|---:|---:|---:|---:|"]
    for o, rows in projections.items():
        for p in rows:
            lines.append(f"| P{o} | {p['dofs']:.0e} | {p['ranks']:,} ({p['nodes_of_24GiB']:,}) | "
                         f"{gib(p['memory_per_rank_target'])} | {gib(p['memory_per_rank_current'])} | "
                         f"{p['ghost_nodes_per_rank']:,.0f} | {p['halo_bytes_per_exchange'] / 1e3:,.0f} kB | "
                         f"{p['seconds_per_solve_compute']:.1f} + {p['seconds_per_solve_communication']:.2f} |")
    p8 = {o: next(p for p in rows if p["dofs"] == 1e8) for o, rows in projections.items()}
    lines += ["", "## What this says for 1e8 unknowns", ""]
    for o, p in p8.items():
        lines.append(f"- P{o}: {p['ranks']:,} ranks on {p['nodes_of_24GiB']:,} such nodes at "
                     f"{gib(p['memory_per_rank_target'])} per rank (target design); a linear solve ~"
                     f"{p['seconds_per_solve_compute'] + p['seconds_per_solve_communication']:.1f} s. "
                     f"Today's replicated design needs {gib(p['memory_per_rank_current'])} per rank: it does not fit.")
    lines += ["", "Where the replicated part R stops fitting in 20 GiB per rank (today's design):", ""]
    for o, m in model.items():
        lines.append(f"- P{o}: about {NODE_MEMORY / m['derived']['replicated_bytes_per_dof'] / 1e6:.1f} M unknowns.")
    (out_dir / "model.md").write_text("\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
