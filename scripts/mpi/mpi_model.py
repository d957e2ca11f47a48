#!/usr/bin/python3
"""A sizing model for distributed runs past this machine, from the
1- and 2-rank measurements of scripts/bench-mpi (reports/mpi/scaling.json).

    /usr/bin/python3 scripts/mpi/mpi_model.py [reports/mpi]

Writes reports/mpi/model.md and model.json: per-rank memory, halo volume, AMG
set-up cost and linear-solve time against rank count for P1-P3 up to 1e9
unknowns. Every number is labelled measured (from scaling.json), derived
(arithmetic on measured numbers) or extrapolated (a stated assumption carried to
sizes and rank counts not run).
"""
import json
import math
import sys
from pathlib import Path

NODE_MEMORY = 20 * 2**30       # usable bytes of a 24 GiB node like this one (assumption: 4 GiB for the OS)
RANKS_PER_NODE = 2             # one rank per core, as measured here
NET_BANDWIDTH = 10e9           # bytes/s between nodes (assumption: a 100 Gb/s class interconnect)
NET_LATENCY = 2e-6             # s per message (assumption)
CYCLE_MESSAGES = 30            # halo messages per V-cycle: ~10 levels x (smoother + residual + prolongation)
SETUP_MESSAGES_PER_LEVEL = 12  # BoomerAMG set-up per level: strength, HMIS sweeps, interpolation and RAP row exchanges
RAP_ROW_BYTES = 12 * 80        # a row of P or A travelling in the set-up: ~80 entries x (8 B value + 4 B index)
ITERATION_GROWTH = 1.10        # AMG-PCG iterations x1.10 per 8x unknowns (measured by the solver sweep: P2 19 -> 21 over 350x)
COARSENING = 8                 # unknowns shrink ~8x per AMG level (HMIS in 3D)
SIZES = [1e6, 1e7, 1e8, 1e9]


def per_order(cases, baseline, whole_mesh):
    out = {}
    for order in sorted({c["order"] for c in cases}):
        one = next(c for c in cases if c["order"] == order and c["ranks"] == 1)
        two = next(c for c in cases if c["order"] == order and c["ranks"] == 2)
        n, nodes = one["dofs"], one["nodes"]
        m1, m2 = max(one["peak_rss_bytes_per_rank"]), max(two["peak_rss_bytes_per_rank"])
        r1, r2 = one["per_rank"][0], two["per_rank"]
        setup1 = r1["amg_setup_seconds"] / r1["amg_setups"]
        setup2 = max(r["amg_setup_seconds"] / r["amg_setups"] for r in r2)
        its1, its2 = r1["krylov_iterations"] / r1["krylov_solves"], r2[0]["krylov_iterations"] / r2[0]["krylov_solves"]
        matvec2 = [r["matvec_receive_values"] for r in r2]
        ghosts2 = max(r["ghost_nodes"] for r in r2)
        out[order] = {
            "measured": {
                "dofs": n, "nodes": nodes, "baseline_rss": baseline, "rss_1_rank": m1, "rss_2_ranks": m2,
                "krylov_seconds_1_rank": r1["krylov_seconds"], "krylov_seconds_2_ranks": max(r["krylov_seconds"] for r in r2),
                "krylov_iterations_per_solve_1_rank": its1, "krylov_iterations_per_solve_2_ranks": its2,
                "linear_solves": r1["krylov_solves"],
                "amg_setup_seconds_1_rank": setup1, "amg_setup_seconds_2_ranks": setup2,
                "matvec_receive_values_2_ranks": matvec2, "ghost_nodes_2_ranks": ghosts2,
                "pattern_nonzeros_1_rank": r1["pattern_nonzeros"],
                "pattern_nonzeros_2_ranks": [r["pattern_nonzeros"] for r in r2],
                "speedup_2_ranks": one["wall_seconds_median"] / two["wall_seconds_median"],
                "wall_seconds_1_rank": one["wall_seconds_median"], "wall_seconds_2_ranks": two["wall_seconds_median"],
            },
            "derived": {
                # M(K) = B + R N + D N / K: D through the two runs of generated
                # pieces (R = 0 there); for the whole-mesh path, R cannot be below
                # what the mesh itself takes (counted from its size: coordinates,
                # connectivity and the partition's work arrays).
                # The generated pieces (these runs) have no replicated input by
                # construction; the whole-mesh path's R is measured by building it.
                "replicated_bytes_per_dof_measured": whole_mesh_bytes(*whole_mesh, order=order),
                "input_mesh_bytes_per_dof": input_mesh_bytes(order, nodes, r1["elements"]) / n,
                "distributed_bytes_per_dof": 2 * (m1 - m2) / n,
                "krylov_seconds_per_dof_per_iteration": r1["krylov_seconds"] / r1["krylov_iterations"] / n,
                "amg_setup_seconds_per_dof": setup1 / n,
                "amg_setup_efficiency_2_ranks": setup1 / (2 * setup2),
                "krylov_efficiency_2_ranks": r1["krylov_seconds"] / (2 * max(r["krylov_seconds"] for r in r2)),
                # One cut plane through a cube of `nodes` nodes: values received per
                # matrix-vector product (mean of the two sides) and ghost nodes.
                "matvec_plane_coefficient": (sum(matvec2) / 2) / nodes ** (2 / 3),
                "ghost_plane_coefficient": ghosts2 / nodes ** (2 / 3),
                "nodes_per_dof": nodes / n,
            },
        }
    for m in out.values():
        d = m["derived"]
        d["replicated_bytes_per_dof"] = max(d["replicated_bytes_per_dof_measured"], d["input_mesh_bytes_per_dof"])
    return out


def whole_mesh_bytes(whole_mesh, baseline, order):
    """Bytes per DOF of building the whole input mesh (measured: `hofem mesh` on the cube,
    less `hofem mesh` on one cell)."""
    c = next(c for c in whole_mesh if c["order"] == order)
    return (c["peak_rss_bytes"] - baseline) / c["dofs"]


def input_mesh_bytes(order, nodes, elements):
    """The whole mesh every rank builds before keeping its piece: 3 doubles per node, the
    connectivity (4-byte ids, (p+1)(p+2)(p+3)/6 per tet), RCB's centroids and order (32 B per
    element), the part and owner labels (4 B per element and per node) and the piece's
    renumbering (4 B per node)."""
    per_element = (order + 1) * (order + 2) * (order + 3) // 6
    return nodes * (24 + 4 + 4) + elements * (4 * per_element + 32 + 4)


def project(model, order, dofs, replicated_input):
    m, d = model[order]["measured"], model[order]["derived"]
    fixed = m["baseline_rss"] + (d["replicated_bytes_per_dof"] * dofs if replicated_input else 0.0)
    per_dof = d["distributed_bytes_per_dof"]
    if fixed >= NODE_MEMORY / RANKS_PER_NODE:
        return None  # does not fit at any rank count
    ranks = max(1, math.ceil(dofs * per_dof / (NODE_MEMORY / RANKS_PER_NODE - fixed)))
    ranks += ranks % 2 if ranks > 1 else 1  # whole nodes of 2 ranks
    dofs_per_rank = dofs / ranks
    nodes_per_rank = dofs_per_rank * d["nodes_per_dof"]
    face = nodes_per_rank ** (2 / 3)
    # Cubic RCB parts: a matrix-vector product receives from all 6 faces; the
    # problem's own halo (force sums) has ghosts on the 3 faces lower ranks own.
    matvec_values = 6 * d["matvec_plane_coefficient"] * face
    ghosts = 3 * d["ghost_plane_coefficient"] * face
    growth = ITERATION_GROWTH ** (math.log(dofs / m["dofs"]) / math.log(8))
    iterations = m["krylov_iterations_per_solve_1_rank"] * growth
    compute = d["krylov_seconds_per_dof_per_iteration"] * dofs_per_rank * iterations
    comm = iterations * CYCLE_MESSAGES * (NET_LATENCY + 8 * matvec_values / NET_BANDWIDTH)
    levels = max(1, math.ceil(math.log(dofs / 1e3) / math.log(COARSENING)))
    setup_compute = d["amg_setup_seconds_per_dof"] * dofs_per_rank
    setup_comm = levels * SETUP_MESSAGES_PER_LEVEL * (NET_LATENCY + matvec_values / 3 * RAP_ROW_BYTES / NET_BANDWIDTH)
    return {
        "dofs": dofs, "ranks": ranks, "nodes_of_24GiB": math.ceil(ranks / RANKS_PER_NODE),
        "memory_per_rank": fixed + per_dof * dofs_per_rank,
        "ghost_nodes_per_rank": ghosts, "matvec_receive_bytes": 8 * matvec_values,
        "krylov_iterations": iterations,
        "seconds_per_solve_compute": compute, "seconds_per_solve_communication": comm,
        "amg_levels": levels, "amg_setup_seconds_compute": setup_compute, "amg_setup_seconds_communication": setup_comm,
    }


def setup_against_ranks(model, order, dofs):
    """AMG set-up seconds for a fixed problem over rank counts (strong scaling of the set-up)."""
    m, d = model[order]["measured"], model[order]["derived"]
    rows = []
    for ranks in [2, 8, 64, 512, 4096]:
        per_rank = dofs / ranks
        face = (per_rank * d["nodes_per_dof"]) ** (2 / 3)
        values = 6 * d["matvec_plane_coefficient"] * face
        levels = max(1, math.ceil(math.log(dofs / 1e3) / math.log(COARSENING)))
        compute = d["amg_setup_seconds_per_dof"] * per_rank
        comm = levels * SETUP_MESSAGES_PER_LEVEL * (NET_LATENCY + values / 3 * RAP_ROW_BYTES / NET_BANDWIDTH)
        rows.append({"ranks": ranks, "compute": compute, "communication": comm})
    return rows


def gib(b):
    return f"{b / 2**30:.2f} GiB" if b >= 2**30 else f"{b / 2**20:.0f} MiB"


def main():
    out_dir = Path(sys.argv[1] if len(sys.argv) > 1 else "reports/mpi")
    scaling = json.loads((out_dir / "scaling.json").read_text())
    model = per_order(scaling["cases"], scaling["baseline_rss_bytes"],
                      (scaling["whole_mesh_input"], scaling["whole_mesh_baseline_rss_bytes"]))
    projections = {o: [project(model, o, n, False) for n in SIZES] for o in model}
    replicated = {o: [project(model, o, n, True) for n in SIZES] for o in model}
    setup = {o: setup_against_ranks(model, o, 1e8) for o in model}
    assumptions = {"node_memory": NODE_MEMORY, "ranks_per_node": RANKS_PER_NODE, "net_bandwidth": NET_BANDWIDTH,
                   "net_latency": NET_LATENCY, "cycle_messages": CYCLE_MESSAGES,
                   "setup_messages_per_level": SETUP_MESSAGES_PER_LEVEL, "rap_row_bytes": RAP_ROW_BYTES,
                   "iteration_growth_per_8x": ITERATION_GROWTH, "coarsening": COARSENING}
    (out_dir / "model.json").write_text(json.dumps({"model": model, "projections": projections,
                                                    "projections_replicated_input": replicated,
                                                    "amg_setup_against_ranks_1e8": setup,
                                                    "assumptions": assumptions}, indent=1))
    L = ["# Sizing distributed runs", "",
         "Made by `scripts/mpi/mpi_model.py` from `reports/mpi/scaling.json` (`scripts/bench-mpi`: the Neo-Hookean",
         "manufactured solution on 1 and 2 ranks of this 2-core, 24 GiB machine, one thread per rank, medians of 3).",
         "Each rank keeps only its piece of the mesh (its elements, owned and ghost nodes); pattern, element",
         "data, vectors, hypre's matrix and AMG hierarchy are per piece. Two input paths: the cube of",
         "`hofem mms --distributed` (convergence studies, solver sweeps) is generated piece by piece, so no rank",
         "ever holds it whole; scenes and mesh files are built whole on every rank, partitioned (RCB) and",
         "dropped to the piece, so that input is replicated (R below).", "",
         "## Measured (per order)", "",
         "| order | DOFs | peak RSS / rank, 1 rank | 2 ranks | wall s, 1 rank | 2 ranks | speed-up | Krylov its / solve, 1 / 2 ranks | AMG set-up s, 1 / 2 ranks | Krylov s, 1 / 2 ranks | values received / matvec, ranks 0, 1 |",
         "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for o, m in model.items():
        x = m["measured"]
        L.append(f"| P{o} | {x['dofs']:,} | {gib(x['rss_1_rank'])} | {gib(x['rss_2_ranks'])} | "
                 f"{x['wall_seconds_1_rank']:.2f} | {x['wall_seconds_2_ranks']:.2f} | {x['speedup_2_ranks']:.2f} | "
                 f"{x['krylov_iterations_per_solve_1_rank']:.1f} / {x['krylov_iterations_per_solve_2_ranks']:.1f} | "
                 f"{x['amg_setup_seconds_1_rank']:.3f} / {x['amg_setup_seconds_2_ranks']:.3f} | "
                 f"{x['krylov_seconds_1_rank']:.2f} / {x['krylov_seconds_2_ranks']:.2f} | "
                 f"{x['matvec_receive_values_2_ranks'][0]:,}, {x['matvec_receive_values_2_ranks'][1]:,} |")
    base = next(iter(model.values()))["measured"]["baseline_rss"]
    L += ["", f"Baseline (MPI, hypre and the program on a 1-cell mesh): {gib(base)} peak RSS.",
          "Communication per Krylov iteration (measured, fine level): a matrix-vector product receives the",
          "values above, 8 bytes each; the V-cycle's coarser levels add exchanges not counted here.", "",
          "## Distributed solver options (measured, one run each)", "",
          "| case | ranks | options | Krylov its / solve | AMG set-up s | Krylov s | total s |",
          "|---|---:|---|---:|---:|---:|---:|",
          *[f"| P{r['order']} n={r['n']} | {r['ranks']} | {r['options']} | {r['krylov_iterations_per_solve']:.1f} | "
            f"{r['amg_setup_seconds_per_setup']:.3f} | {r['krylov_seconds']:.2f} | {r['total_seconds']:.2f} |"
            for r in scaling.get("solver_options", [])], "",
          "## Derived (arithmetic on the measurements)", "",
          "Memory per rank as M(K) = B + R N + D N / K: B the baseline; D, what is split, through the two runs",
          "of generated pieces (R = 0 there by construction); R, what every rank holds whatever K on the",
          "whole-mesh path (scenes, mesh files): the measured peak of building the whole cube (`hofem mesh`),",
          "at least the mesh's own size counted from its nodes and elements.", "",
          "| order | R measured, bytes/DOF | mesh counted, bytes/DOF | D, bytes/DOF | Krylov s per DOF per iteration | AMG set-up s per DOF | set-up efficiency 1->2 | Krylov efficiency 1->2 | matvec values = c nodes^(2/3), c |",
          "|---|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for o, m in model.items():
        d = m["derived"]
        L.append(f"| P{o} | {d['replicated_bytes_per_dof_measured']:.0f} | {d['input_mesh_bytes_per_dof']:.0f} | "
                 f"{d['distributed_bytes_per_dof']:.0f} | "
                 f"{d['krylov_seconds_per_dof_per_iteration']:.2e} | {d['amg_setup_seconds_per_dof']:.2e} | "
                 f"{d['amg_setup_efficiency_2_ranks']:.2f} | {d['krylov_efficiency_2_ranks']:.2f} | "
                 f"{d['matvec_plane_coefficient']:.2f} |")
    L += ["", "## Extrapolated", "",
          "Assumptions (not measured): 20 GiB usable per 24 GiB node, 2 ranks per node; cubic RCB parts (a",
          "matrix-vector product receives on 6 faces, the problem's halo has ghosts on 3); Krylov iterations",
          "growing x1.10 per 8x unknowns (the solver sweep's measured AMG scaling) from the 1-rank count; "
          f"{CYCLE_MESSAGES} halo messages per V-cycle and {SETUP_MESSAGES_PER_LEVEL} per AMG level in the set-up,",
          f"{NET_LATENCY * 1e6:.0f} us and {NET_BANDWIDTH / 1e9:.0f} GB/s; set-up rows of ~{RAP_ROW_BYTES} bytes; "
          f"{COARSENING}x coarsening per level. Compute per rank scales with the",
          "measured 1-rank seconds per DOF (the 2-rank efficiencies above say how much is lost on this machine).", "",
          "### Input generated (or read) piece by piece: R = 0 (the `hofem mms --distributed` cube today)", "",
          "| order | DOFs | ranks (nodes) | memory / rank | ghost nodes / rank | received / matvec | Krylov its | solve s: compute + comm | AMG levels | AMG set-up s: compute + comm |",
          "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for o, rows in projections.items():
        for p in rows:
            L.append(f"| P{o} | {p['dofs']:.0e} | {p['ranks']:,} ({p['nodes_of_24GiB']:,}) | {gib(p['memory_per_rank'])} | "
                     f"{p['ghost_nodes_per_rank']:,.0f} | {p['matvec_receive_bytes'] / 1e3:,.0f} kB | "
                     f"{p['krylov_iterations']:.0f} | {p['seconds_per_solve_compute']:.1f} + "
                     f"{p['seconds_per_solve_communication']:.2f} | {p['amg_levels']} | "
                     f"{p['amg_setup_seconds_compute']:.2f} + {p['amg_setup_seconds_communication']:.3f} |")
    L += ["", "### Whole input mesh on every rank (scenes and mesh files today): R as measured", "",
          "| order | DOFs | ranks (nodes) | memory / rank |", "|---|---:|---:|---:|"]
    for o, rows in replicated.items():
        for n, p in zip(SIZES, rows):
            L.append(f"| P{o} | {n:.0e} | " + ("does not fit: the input mesh alone exceeds a rank's memory |" if p is None else
                     f"{p['ranks']:,} ({p['nodes_of_24GiB']:,}) | {gib(p['memory_per_rank'])} |"))
    L += ["", "### AMG set-up against rank count, 1e8 unknowns (compute + communication, s)", "",
          "| order | " + " | ".join(f"K = {r['ranks']:,}" for r in next(iter(setup.values()))) + " |",
          "|---|" + "---:|" * len(next(iter(setup.values())))]
    for o, rows in setup.items():
        L.append(f"| P{o} | " + " | ".join(f"{r['compute']:.2f} + {r['communication']:.3f}" for r in rows) + " |")
    shares = [(o, rows[0]["communication"] / (rows[0]["compute"] + rows[0]["communication"]),
               rows[-1]["communication"] / (rows[-1]["compute"] + rows[-1]["communication"])) for o, rows in setup.items()]
    L += ["", "The set-up's compute falls as N/K; its modelled communication only as (N/K)^(2/3) plus a latency",
          "term per level, so its share grows with K: " + ", ".join(
              f"P{o} {a * 100:.1f} % at K = {setup[o][0]['ranks']:,} -> {b * 100:.0f} % at K = {setup[o][-1]['ranks']:,}"
              for o, a, b in shares) + ".",
          "Not modelled: load imbalance on the coarse levels and the agglomeration of the coarsest grids, which limit",
          "BoomerAMG's set-up scaling in practice long before the latency term does. On this machine the measured",
          "set-up efficiency from 1 to 2 ranks is below the Krylov efficiency (table above).", "",
          "## What this says for 1e8 unknowns", ""]
    for o, rows in projections.items():
        p = next(p for p in rows if p["dofs"] == 1e8)
        q = next(q for n, q in zip(SIZES, replicated[o]) if n == 1e8)
        today = "does not fit" if q is None else f"{q['ranks']:,} ranks at {gib(q['memory_per_rank'])} per rank"
        L.append(f"- P{o}: {p['ranks']:,} ranks on {p['nodes_of_24GiB']:,} such nodes at {gib(p['memory_per_rank'])} "
                 f"per rank with the input generated per piece (the cube); a linear solve ~"
                 f"{p['seconds_per_solve_compute'] + p['seconds_per_solve_communication']:.1f} s, an AMG set-up ~"
                 f"{p['amg_setup_seconds_compute'] + p['amg_setup_seconds_communication']:.1f} s. "
                 f"A scene or mesh file, built whole on every rank: {today}.")
    L += ["", "Where the whole input mesh alone fills a rank's 10 GiB (the limit of scenes and mesh files; a",
          "partitioned mesh file, e.g. Gmsh's partitioned .msh read per rank, would lift it):", ""]
    for o, m in model.items():
        r = m["derived"]["replicated_bytes_per_dof"]
        L.append(f"- P{o}: about {NODE_MEMORY / RANKS_PER_NODE / r / 1e6:.0f} M unknowns.")
    (out_dir / "model.md").write_text("\n".join(L) + "\n")
    print("\n".join(L))


if __name__ == "__main__":
    main()
