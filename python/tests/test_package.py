"""The package as a new user meets it: its version and types."""

import importlib.metadata
import pathlib
import re
import subprocess
import sys

import pytest

import lanecast
from conftest import REPO


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


def test_the_stub_matches_the_extension():
    pytest.importorskip("mypy")
    run = subprocess.run([sys.executable, "-m", "mypy.stubtest", "lanecast._lanecast"],
                         capture_output=True, text=True, timeout=300)
    assert run.returncode == 0, run.stdout + run.stderr
