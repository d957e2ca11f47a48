"""Reads hofem's .vtu files back with meshio (Debian's python3-meshio), in all three
encodings (--vtu-format ascii, binary, zlib), and checks them.

Usage: check_vtu_roundtrip.py HOFEM WORKDIR

For each element kind (Tet4, Tet10, Tet20 = VTK Lagrange tetrahedron of order 3,
Hex8, Hex20) `hofem mms --vtu` writes a 4^3-cube solution (point fields
displacement and exact_displacement, cell field l2_error) once per encoding. Checked:
  * the three encodings read back identically, bit for bit: points, connectivity,
    cell type and every field (binary stores the doubles' bytes; ASCII prints 17
    significant digits, which round-trip IEEE doubles exactly: Goldberg 1991, §4.2,
    and C++'s max_digits10 = 17 for double) - so no tolerance;
  * the counts and the cell type against numbers worked out by hand, not by hofem;
  * the VTK node order, from VTK's own definitions (vtkQuadraticTetra.h,
    vtkQuadraticHexahedron.h, vtkHigherOrderTetra.cxx): mid-edge nodes at the
    midpoints of VTK's edge list, Lagrange points at the thirds of the edges and
    face centroids - so a wrong permutation fails even if all encodings agree.
The 4^3 meshes make Tet20's arrays (2197 points x 24 bytes) span two 32 KiB zlib
blocks, the second partial. Also `hofem mesh --vtu-format zlib`: element_id = 0..n-1.
"""
import subprocess
import sys
import warnings
from pathlib import Path

import meshio
import numpy as np

N = 4  # cubes per side
FORMATS = ("ascii", "binary", "zlib")
# (cell, order): meshio's name of the VTK cell type, points, cells - by hand: a tet
# box of N^3 cubes, 6 tets each, has (N p + 1)^3 nodes; Hex20 = the (N+1)^3 vertices
# plus the 3 N (N+1)^2 edge midpoints.
CASES = {
    ("tet", 1): ("tetra", (N + 1) ** 3, 6 * N**3),
    ("tet", 2): ("tetra10", (2 * N + 1) ** 3, 6 * N**3),
    ("tet", 3): ("VTK_LAGRANGE_TETRAHEDRON", (3 * N + 1) ** 3, 6 * N**3),
    ("hex", 1): ("hexahedron", (N + 1) ** 3, N**3),
    ("hex", 2): ("hexahedron20", (N + 1) ** 3 + 3 * N * (N + 1) ** 2, N**3),
}
TET_EDGES = [(0, 1), (1, 2), (2, 0), (0, 3), (1, 3), (2, 3)]  # vtkQuadraticTetra.h, vtkHigherOrderTetra
HEX_EDGES = [(0, 1), (1, 2), (2, 3), (3, 0), (4, 5), (5, 6), (6, 7), (7, 4), (0, 4), (1, 5), (2, 6), (3, 7)]
TET_FACES = [(0, 1, 3), (2, 3, 1), (0, 3, 2), (0, 2, 1)]  # vtkHigherOrderTetra face order (vtu_writer.hpp)
# Coordinates are sums of a few multiples of 1/12: 1e-12 m is ~1e4 ulps of 1.0, far
# below the 1/12 spacing, so a misplaced node cannot pass.
TOL = 1e-12


def fail(msg):
    print(f"check_vtu_roundtrip: FAIL: {msg}")
    sys.exit(1)


def read(path):
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # meshio warns and drops cells it cannot read: that is a failure
        return meshio.read(path)


def geometry(name, pts, cells, order):
    """The node order against VTK's definitions: returns a message or None."""
    x = pts[cells]  # cells x nodes x 3
    if name.startswith("tet") or name.startswith("VTK"):
        v = x[:, :4]
        vol = np.einsum("ij,ij->i", v[:, 1] - v[:, 0], np.cross(v[:, 2] - v[:, 0], v[:, 3] - v[:, 0]))
        if np.any(vol <= 0):
            return "a tetrahedron's vertices 0-3 are not right-handed (vtkTetra)"
        k = 4
        for a, b in TET_EDGES:
            for i in range(1, order):
                if not np.allclose(x[:, k], v[:, a] + i / order * (v[:, b] - v[:, a]), atol=TOL):
                    return f"node {k} is not at {i}/{order} of edge {a}->{b}"
                k += 1
        if order == 3:
            for a, b, c in TET_FACES:
                if not np.allclose(x[:, k], (v[:, a] + v[:, b] + v[:, c]) / 3, atol=TOL):
                    return f"node {k} is not the centroid of face {a},{b},{c}"
                k += 1
    elif order == 2:
        for k, (a, b) in enumerate(HEX_EDGES, start=8):
            if not np.allclose(x[:, k], (x[:, a] + x[:, b]) / 2, atol=TOL):
                return f"Hex20 node {k} is not the midpoint of edge {a}-{b}"
    return None


def check_case(hofem, work, cell, order):
    kind, npoints, ncells = CASES[(cell, order)]
    meshes = {}
    for fmt in FORMATS:
        path = work / f"{cell}{order}_{fmt}.vtu"
        subprocess.run([hofem, "mms", "--problem", "linear", "--cell", cell, "--order", str(order), "--n", str(N),
                        "--vtu", str(path), "--vtu-format", fmt], check=True, stdout=subprocess.DEVNULL)
        head = path.read_bytes()[:400]
        if (b"AppendedData" in path.read_bytes()) != (fmt != "ascii") or \
                (b"vtkZLibDataCompressor" in head) != (fmt == "zlib"):
            fail(f"{path}: not written in the {fmt} encoding")
        meshes[fmt] = read(path)
    ref = meshes["ascii"]
    tag = f"{cell} order {order}"
    if len(ref.cells) != 1 or not ref.cells[0].type.startswith(kind):
        fail(f"{tag}: cell blocks {[c.type for c in ref.cells]}, expected one of {kind}")
    if ref.points.shape != (npoints, 3) or ref.cells[0].data.shape[0] != ncells:
        fail(f"{tag}: {ref.points.shape[0]} points, {ref.cells[0].data.shape[0]} cells; expected {npoints}, {ncells}")
    msg = geometry(kind, ref.points, ref.cells[0].data, order)
    if msg:
        fail(f"{tag}: {msg}")
    for fmt in ("binary", "zlib"):
        m = meshes[fmt]
        same = (np.array_equal(m.points, ref.points) and len(m.cells) == 1 and m.cells[0].type == ref.cells[0].type
                and np.array_equal(m.cells[0].data, ref.cells[0].data)
                and sorted(m.point_data) == sorted(ref.point_data) == ["displacement", "exact_displacement"]
                and all(np.array_equal(m.point_data[k], ref.point_data[k]) for k in ref.point_data)
                and list(m.cell_data) == list(ref.cell_data) == ["l2_error"]
                and np.array_equal(m.cell_data["l2_error"][0], ref.cell_data["l2_error"][0]))
        if not same:
            fail(f"{tag}: the {fmt} file does not read back as the ascii one")
    print(f"  {tag}: {npoints} points, {ncells} {ref.cells[0].type} cells, 3 encodings identical")


def main():
    hofem, work = sys.argv[1], Path(sys.argv[2])
    work.mkdir(parents=True, exist_ok=True)
    for cell, order in CASES:
        check_case(hofem, work, cell, order)
    path = work / "mesh_hex20_zlib.vtu"
    subprocess.run([hofem, "mesh", "--box", "2", "--cell", "hex", "--order", "2", "--vtu", str(path),
                    "--vtu-format", "zlib"], check=True, stdout=subprocess.DEVNULL)
    ids = np.ravel(read(path).cell_data["element_id"][0])
    if not np.array_equal(ids, np.arange(8)):
        fail(f"{path}: element_id {ids}, expected 0..7")
    print("check_vtu_roundtrip: OK, 5 element kinds x 3 encodings + hofem mesh zlib")


if __name__ == "__main__":
    main()
