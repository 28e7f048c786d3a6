"""Journey: `pip install` the package into an environment that has numpy and nothing else.

A student who only wants the geometry runs `make dist` (or downloads the wheel) and installs it
next to numpy. `import ddg`, the three curvatures, the flow and the homework checks must work
there; the optional parts must fail with a message that names the extra to install.
"""

import subprocess
import sys

from journey_helpers import OFFLINE_PIP, copy_repository, fresh_venv, run

SCRIPT = r"""
import importlib, subprocess, sys
import numpy as np
import ddg

installed = subprocess.run([sys.executable, "-m", "pip", "list", "--format=freeze"],
                           capture_output=True, text=True).stdout.lower()
names = {line.split("==")[0] for line in installed.split()}
assert names <= {"numpy", "ddg-plane-curves", "ddg_plane_curves", "pip", "setuptools"}, names
assert "site-packages" in ddg.__file__, ddg.__file__  # the installed wheel, not the source tree

square = ddg.DiscreteCurve([[0, 0], [0, 1], [1, 1], [1, 0]])
k = {kind: square.curvature(kind) for kind in ddg.CURVATURES}
assert np.allclose(k["angle"], np.pi / 2) and np.allclose(k["sine"], np.sqrt(2))
assert np.allclose(k["tangent"], 2.0)
run = ddg.flow.flow(ddg.regular_polygon(24), "sine", 0.05)
assert run.stopped == "reached t_end" and run.areas[-1] < run.areas[0]
print("geometry ok:", {kind: round(float(v[0]), 6) for kind, v in k.items()}, run.stopped)

from ddg import explore  # its scenes need numpy only; widgets and shapely come with the extra
scene = explore.PolygonExplorer().scene(12, "ellipse", "angle")
assert "<svg" in explore.svg(scene, 0)
uses = {
    "ddg.plot": lambda: importlib.import_module("ddg.plot"),
    "ddg.explore widgets": lambda: explore.polygon_explorer().widget(),
    "ddg.explore shapely": lambda: explore.InflationExplorer().compute(0.3, "non-convex star", "offset"),
}
extras = {"ddg.plot": "plot", "ddg.explore widgets": "explore", "ddg.explore shapely": "explore"}
# the students' checks need numpy only: their public input and its right results ship in the wheel
from ddg import checks
verdict = checks.run("minkowski_area", lambda curve, eps: 0.0, 0)
assert not verdict and "expected" in verdict.problem, verdict
assert checks.run("turning_angles", lambda v: np.zeros(len(v)), 0).inputs == 14
for name, use in uses.items():
    try:
        use()
    except ImportError as error:
        assert f'pip install "ddg-plane-curves[{extras[name]}]"' in str(error), str(error)
        print(f"{name}: {error}")
    else:
        raise AssertionError(f"{name} worked without its extra")
try:
    ddg.plot
except ImportError as error:
    assert "ddg-plane-curves[plot]" in str(error)
else:
    raise AssertionError("ddg.plot worked without matplotlib")
"""


def test_wheel_installs_alone_and_names_the_missing_extras(tmp_path):
    copy = copy_repository(tmp_path / "repo")
    run(["make", "dist"], cwd=copy)
    wheels, sdists = list((copy / "dist").glob("*.whl")), list((copy / "dist").glob("*.tar.gz"))
    assert len(wheels) == 1 and len(sdists) == 1, list((copy / "dist").iterdir())

    python = fresh_venv(tmp_path / "venv")
    run([str(python), "-m", "pip", "install", "--quiet", str(wheels[0])], env=OFFLINE_PIP)
    result = run([str(python), "-c", SCRIPT], cwd=tmp_path)  # not the repository: no ddg/ next to it
    assert "geometry ok" in result.stdout
    assert 'ddg.plot: matplotlib is not installed; this part of ddg needs the extra [plot]' in result.stdout
    names = subprocess.run([sys.executable, "-m", "zipfile", "-l", str(wheels[0])], capture_output=True, text=True,
                           check=True).stdout
    assert "ddg/scene.py" in names and "instructor" not in names  # students' package only, no grading code


def test_pip_install_of_a_checkout_leaves_nothing_git_would_show(tmp_path):
    copy = copy_repository(tmp_path / "repo", with_venv=False)
    run(["git", "init", "-q"], cwd=copy)

    def untracked():
        return run(["git", "ls-files", "--others", "--exclude-standard"], cwd=copy).stdout.split()

    before = untracked()
    python = fresh_venv(tmp_path / "venv")
    run([str(python), "-m", "pip", "install", "--quiet", "."], cwd=copy, env=OFFLINE_PIP)
    assert (copy / "build").is_dir()  # setuptools' build folder: ignored
    assert untracked() == before
