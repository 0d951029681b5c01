#!/usr/bin/env bash
# What CI runs for the Python package, from the repository root of a clean clone:
#   bash python/ci.sh
# Needs python3 (3.9 or later) with venv and pip, cargo, and PyPI and crates.io. Runs README's
# four Python commands, in order and as written (python/tests/test_package.py checks that they
# are these lines): the command line (the tests' native reference), a venv under target/, the
# package with its dask and test extras (maturin, from PyPI, as the build backend), the tests.
# Then lints the binding crate and checks the type stub with mypy. Exits non-zero when
# anything fails or no test ran.
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD

# README "Python", line by line; CI adds only where the extension builds: in its own target
# folder, so it never waits on the main build's lock.
cargo build --release --bin lanecast   # the tests' reference
python3 -m venv target/py-venv && . target/py-venv/bin/activate
export CARGO_TARGET_DIR="$root/target/python"
pip install "./python[dask,test]"      # or "./python": no Dask, no pytest and mypy
pytest python/tests

# The binding crate lints clean (it is not a default member, so the root's clippy skips it;
# --no-deps: the library is linted by .ci/run).
PYO3_PYTHON="$root/target/py-venv/bin/python" \
    cargo clippy -p lanecast-python --release --no-deps -- -D warnings

# Types: the stub matches the built extension (stubtest), and the package and the examples
# type-check against it.
python -m mypy.stubtest lanecast._lanecast
mypy -p lanecast
mypy python/examples
