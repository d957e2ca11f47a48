"""Pictures of the scenes' final states: reports/scenes/NAME.png for every
reports/scenes/NAME/final.vtu (hofem run --no-frames --final-frame), or the last
frame_NNNNN.vtu of a scene run with all its frames.

Usage: render_scenes.py REPORTS_DIR

Each picture is the deformed boundary surface, coloured by |displacement| (m):
the boundary faces of the tetrahedra/hexahedra are the faces that belong to one
cell only; each is drawn through its vertices only (a triangle or a quad; the
mid-edge nodes of curved elements are left out, so curved faces look flat) and
moved by the displacement of those vertices. An embedded (finite cell) scene's
picture is its embedded surface (final_surface.vtu, triangles), not the box of
background cells. The files are read with meshio (Debian's python3-meshio).

matplotlib draws polygons back to front by their mean depth (the painter's
algorithm), which puts far faces over near ones where large faces overlap (the
twisted cylinder's neck). So the view is orthographic, and when the surface is
consistently oriented (every directed edge met once, its reverse once) the faces
turned away from the viewer are dropped, as a renderer's back-face culling does;
the faces are then shaded by their angle to a light at the viewer (60-100 % of
the colour) so the shape reads.
"""
import sys
import time
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import meshio  # noqa: E402
import numpy as np  # noqa: E402
from mpl_toolkits.mplot3d.art3d import Poly3DCollection  # noqa: E402

# Faces of the reference cells through their vertex nodes, outward for VTK's
# vertex order (vtkTetra, vtkHexahedron). Higher-order cells list their vertices first.
TET_FACES = np.array([[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]])
HEX_FACES = np.array([[0, 3, 2, 1], [4, 5, 6, 7], [0, 1, 5, 4], [1, 2, 6, 5], [2, 3, 7, 6], [3, 0, 4, 7]])


def cell_faces(block_type, cells):
    """All faces (vertex ids) of a block of cells, or None for a surface of triangles."""
    if block_type == "triangle":
        return cells[:, :3]
    if block_type.startswith("tetra") or block_type.startswith("VTK_LAGRANGE_TETRAHEDRON"):
        return cells[:, TET_FACES].reshape(-1, 3)
    if block_type.startswith("hexahedron"):
        return cells[:, HEX_FACES].reshape(-1, 4)
    raise ValueError(f"no faces for cell type {block_type}")


def boundary_faces(faces, surface):
    """The faces used by one cell only (each interior face is shared by two)."""
    if surface:
        return faces
    key = np.sort(faces, axis=1)
    _, inverse, counts = np.unique(key, axis=0, return_inverse=True, return_counts=True)
    return faces[counts[inverse.ravel()] == 1]


ELEV, AZIM = 30.0, -60.0  # matplotlib's default view


def consistently_oriented(faces):
    """Each directed edge once and its reverse once: a closed, consistently oriented surface."""
    edges = np.stack([faces, np.roll(faces, -1, axis=1)], axis=-1).reshape(-1, 2)
    directed = np.unique(edges, axis=0)
    if len(directed) != len(edges):
        return False
    reverse = np.unique(edges[:, ::-1], axis=0)
    return np.array_equal(directed, reverse)


def face_normals(x, faces):
    """Area-weighted normals (from the first three vertices; quads' diagonals for k = 4)."""
    if faces.shape[1] == 4:
        return np.cross(x[faces[:, 2]] - x[faces[:, 0]], x[faces[:, 3]] - x[faces[:, 1]])
    return np.cross(x[faces[:, 1]] - x[faces[:, 0]], x[faces[:, 2]] - x[faces[:, 0]])


def visible(x, faces, eye):
    """The faces turned towards the eye and the shade of each (|cos| to the eye)."""
    n = face_normals(x, faces)
    length = np.maximum(np.linalg.norm(n, axis=1), 1e-300)
    facing = n @ eye / length
    if consistently_oriented(faces):
        # Outward if the enclosed volume (divergence theorem, sum of x . n / 3) is positive.
        centre = x[faces].mean(axis=1)
        if np.einsum("ij,ij->", centre, n) < 0.0:
            facing = -facing
        keep = facing > 0.0
        return faces[keep], facing[keep]
    return faces, np.abs(facing)


def render(vtu, png, title):
    mesh = meshio.read(vtu)
    u = mesh.point_data.get("displacement")
    if u is None:
        raise ValueError(f"{vtu}: no point field 'displacement'")
    x = mesh.points + u
    polys = []
    for block in mesh.cells:
        polys.append(boundary_faces(cell_faces(block.type, block.data), block.type == "triangle"))
    mag = np.linalg.norm(u, axis=1)
    norm = matplotlib.colors.Normalize(vmin=0.0, vmax=max(mag.max(), 1e-300))
    fig = plt.figure(figsize=(4.8, 3.6))
    # The colour bar has an axes of its own, below the picture: placed beside it by
    # fig.colorbar(ax=...), a flat body's z axis (the slingshot) was drawn over it.
    ax = fig.add_axes([0.0, 0.2, 1.0, 0.72], projection="3d")
    ax.view_init(elev=ELEV, azim=AZIM)
    ax.set_proj_type("ortho")
    e, a = np.radians(ELEV), np.radians(AZIM)
    eye = np.array([np.cos(e) * np.cos(a), np.cos(e) * np.sin(a), np.sin(e)])
    for faces in polys:
        faces, shade = visible(x, faces, eye)
        colours = plt.cm.viridis(norm(mag[faces].mean(axis=1)))
        colours[:, :3] *= (0.6 + 0.4 * shade)[:, None]
        coll = Poly3DCollection(x[faces], facecolors=colours, edgecolors="k", linewidths=0.1)
        ax.add_collection3d(coll)
    lo, hi = x.min(axis=0), x.max(axis=0)
    for set_lim, a, b in zip((ax.set_xlim, ax.set_ylim, ax.set_zlim), lo, hi):
        set_lim(a, b if b > a else a + 1e-9)
    ax.set_box_aspect(np.maximum(hi - lo, 1e-3 * (hi - lo).max()))
    ax.set_xlabel("x (m)", fontsize=7)
    ax.set_ylabel("y (m)", fontsize=7)
    ax.set_zlabel("z (m)", fontsize=7)
    ax.tick_params(labelsize=6)
    ax.locator_params(nbins=4)
    bar = fig.colorbar(matplotlib.cm.ScalarMappable(norm=norm, cmap="viridis"), cax=fig.add_axes([0.3, 0.13, 0.4, 0.025]),
                       orientation="horizontal")
    bar.set_label("|displacement| (m)", fontsize=7)
    bar.ax.tick_params(labelsize=6)
    ax.set_title(title, fontsize=9)
    fig.savefig(png, dpi=100)
    plt.close(fig)


def last_state(scene_dir):
    """final(_surface).vtu, or, for a run that wrote every frame, its last frame."""
    frames = sorted(scene_dir.glob("frame_[0-9][0-9][0-9][0-9][0-9].vtu"))
    for stem in ["final"] + ([frames[-1].stem] if frames else []):
        for name in (f"{stem}_surface.vtu", f"{stem}.vtu"):
            if (scene_dir / name).exists():
                return scene_dir / name
    return None


def main():
    reports = Path(sys.argv[1] if len(sys.argv) > 1 else "reports")
    start = time.perf_counter()
    done = 0
    for scene_dir in sorted(p for p in (reports / "scenes").glob("*") if p.is_dir()):
        vtu = last_state(scene_dir)
        if vtu is None:
            continue
        render(vtu, scene_dir.parent / f"{scene_dir.name}.png", scene_dir.name)
        done += 1
    print(f"render_scenes: {done} pictures in {time.perf_counter() - start:.1f} s -> {reports / 'scenes'}/NAME.png")
    if done == 0:
        print(f"render_scenes: no {reports}/scenes/NAME/final.vtu (hofem run --no-frames --final-frame)", file=sys.stderr)
        sys.exit(1)


if __name__ == "__main__":
    main()
