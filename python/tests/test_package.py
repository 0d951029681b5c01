"""The package as a new user meets it: its version and types, README's commands (which
python/ci.sh runs as written), and README's examples, run as files."""

import importlib.metadata
import os
import pathlib
import re
import subprocess
import sys

import pytest

import lanecast
from conftest import REPO

README = (REPO / "README.md").read_text()
SECTION = README[README.index("\n## Python\n"):]
SECTION = SECTION[:SECTION.index("\n## ", 1)]
EXAMPLES = REPO / "python" / "examples"


def test_version_is_the_installed_distributions():
    assert re.fullmatch(r"\d+\.\d+\.\d+.*", lanecast.__version__)
    assert lanecast.__version__ == importlib.metadata.version("lanecast")
    assert "__version__" in lanecast.__all__


def test_the_installed_package_is_typed_and_is_the_one_imported():
    pkg = pathlib.Path(lanecast.__file__).parent
    assert pkg != REPO / "python" / "lanecast", "the tests must import the installed package"
    assert (pkg / "py.typed").is_file()
    stub = (pkg / "_lanecast.pyi").read_text()
    for name in ("class Scene", "class Camera", "class Render", "def shade", "__version__"):
        assert name in stub


def _readme_commands():
    # the indented block after the section's first paragraph: one command a line
    block = re.search(r"\n\n((?:    \S.*\n)+)", SECTION).group(1)
    return [line[4:].rstrip() for line in block.splitlines()]


def test_readme_install_and_test_commands_are_what_ci_runs():
    commands = _readme_commands()
    assert commands[-2].startswith('pip install "./python[dask,test]"')
    assert commands[-1] == "pytest python/tests"
    ci = (REPO / "python" / "ci.sh").read_text().splitlines()
    at = [ci.index(c) for c in commands]  # each line, exactly as written
    assert at == sorted(at), "in README's order"


def test_the_test_extra_installs_what_the_tests_and_ci_need():
    req = importlib.metadata.requires("lanecast") or []
    test = [r for r in req if re.search(r"extra == ['\"]test['\"]", r)]
    assert any(r.startswith("pytest") for r in test) and any(r.startswith("mypy") for r in test)


def _readme_examples():
    blocks = re.findall(r"```python\n(.*?)```", SECTION, re.S)
    named = {}
    for b in blocks:
        m = re.match(r"# python/examples/(\w+\.py):", b)
        assert m, f"a README example that is not a file a test runs:\n{b}"
        named[m.group(1)] = b
    return named


def test_readme_examples_are_the_example_files():
    named = _readme_examples()
    assert set(named) == {"views.py", "dask_views.py"}
    for name, text in named.items():
        assert (EXAMPLES / name).read_text() == text, name


def _run_example(name, tmp_path):
    # from a folder of its own that holds the scenes, as a user's copy of the repository would
    (tmp_path / "scenes").symlink_to(REPO / "scenes")
    return subprocess.run([sys.executable, str(EXAMPLES / name)], cwd=tmp_path,
                          capture_output=True, text=True, timeout=300)


def test_the_views_example_runs_as_written(tmp_path):
    run = _run_example("views.py", tmp_path)
    assert run.returncode == 0, run.stderr
    assert run.stdout.strip() == "(24, 360, 640) int32 float32"
    size = (tmp_path / "views.npz").stat().st_size
    assert size < 16 << 20, size  # compressed: 7 MB, against 44 MB as .npy


def test_the_dask_example_runs_as_written_from_a_file(tmp_path):
    pytest.importorskip("distributed")
    run = _run_example("dask_views.py", tmp_path)
    assert run.returncode == 0, run.stderr
    assert run.stdout.strip() == "24 views done, 0 skipped (already complete), 0 failed"
    # nothing logged as an error at exit (a client left open), no task rendered twice over
    assert "ERROR" not in run.stderr and "Traceback" not in run.stderr, run.stderr
    views = sorted(os.listdir(tmp_path / "out"))
    assert views == [f"view_{v:06d}" for v in range(24)]
    assert not list(tmp_path.glob("*.npz"))


def test_the_stub_matches_the_extension():
    pytest.importorskip("mypy")
    run = subprocess.run([sys.executable, "-m", "mypy.stubtest", "lanecast._lanecast"],
                         capture_output=True, text=True, timeout=300)
    assert run.returncode == 0, run.stdout + run.stderr


TYPED_PROGRAM = """
import pathlib
import numpy as np
import numpy.typing as npt
import lanecast

s: lanecast.Scene = lanecast.Scene.load(SCENE)
source: pathlib.Path = s.source
warnings: list[str] = s.warnings
counts: tuple[int, int, int] = s.counts
cam: lanecast.Camera = s.camera
eye: list[float] = cam.eye
fov: float = cam.fov
out: lanecast.Render = s.render(cam, 8, 6, threads=1)
ids: npt.NDArray[np.int32] = out.ids
depth: npt.NDArray[np.float32] = out.depth
image: npt.NDArray[np.uint8] = out.image(seed=3)
version: str = lanecast.__version__
for name, value, kind in [("source", source, pathlib.Path), ("warnings", warnings, list),
                          ("counts", counts, tuple), ("eye", eye, list), ("fov", fov, float),
                          ("version", version, str)]:
    assert isinstance(value, kind), (name, type(value))
assert ids.dtype == np.dtype(np.int32) and depth.dtype == np.dtype(np.float32)
assert image.dtype == np.dtype(np.uint8)
"""


def test_the_stubs_types_are_the_runtimes(tmp_path):
    # stubtest checks names and signatures; this program's annotations are the types a
    # caller relies on: mypy accepts them against the stub, and the asserts hold at runtime
    pytest.importorskip("mypy")
    from conftest import SCENES
    program = tmp_path / "typed.py"
    program.write_text(f"SCENE = {str(SCENES / 'scene1.sc')!r}\n" + TYPED_PROGRAM)
    run = subprocess.run([sys.executable, str(program)], capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    run = subprocess.run([sys.executable, "-m", "mypy", "--strict", str(program)],
                         capture_output=True, text=True, timeout=300, cwd=tmp_path)
    assert run.returncode == 0, run.stdout + run.stderr
