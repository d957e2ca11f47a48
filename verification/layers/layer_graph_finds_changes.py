"""scripts/checks/layer_graph.py must fail on each kind of disagreement: a layer
including a layer it does not link, a linked layer no longer included, a header
outside parallel/ including <mpi.h>, and a README graph that is not the
targets'. Each is made on a copy (the real tree is read, never changed)."""
import pathlib
import shutil
import sys
import tempfile

scripts, layers_txt, core = sys.argv[1], pathlib.Path(sys.argv[2]), pathlib.Path(sys.argv[3])
sys.path.insert(0, scripts)
import layer_graph as g  # noqa: E402

declared = g.read_declared(layers_txt)
used = g.read_used(core, declared)
assert g.check(declared, used, core) == [], g.check(declared, used, core)

# mesh/ includes quadrature/: dropping the link is an undeclared include.
broken = dict(declared, mesh=[d for d in declared["mesh"] if d != "quadrature"])
assert g.check(broken, used, core) == ["core/mesh/ includes quadrature/, which layer mesh does not link"], \
    g.check(broken, used, core)
# A link no source needs any more.
broken = dict(declared, material=["quadrature"])
assert g.check(broken, used, core) == [
    "core/CMakeLists.txt: layer material links quadrature, but no source of core/material/ includes it"]

with tempfile.TemporaryDirectory() as tmp:
    copy = pathlib.Path(tmp) / "core"
    shutil.copytree(core, copy, ignore=shutil.ignore_patterns("*.cpp", "*.yml"))
    (copy / "assembly" / "halo_user.hpp").write_text("#pragma once\n#include <mpi.h>\n")
    assert g.mpi_outside_parallel(copy) == ["assembly/halo_user.hpp"], g.mpi_outside_parallel(copy)
    # The README block written for another graph differs from this one's.
    other = dict(declared, study=declared["study"][:-1])
    assert g.render(other) != g.render(declared)
    readme = pathlib.Path(tmp) / "README.md"
    readme.write_text("# x\n\n" + g.render(other) + "\n")
    sys.argv = ["layer_graph.py", "--layers", str(layers_txt), "--readme", str(readme), "--core", str(core)]
    assert g.main() == 1
    sys.argv.append("--write")
    assert g.main() == 0 and g.render(declared) in readme.read_text()
print("layer_graph finds every change")
