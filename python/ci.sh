#!/usr/bin/env bash
# What CI runs for the Python package, from the repository root of a clean clone:
#   bash python/ci.sh
# Needs python3 (3.9 or later) with venv and pip, cargo, and PyPI and crates.io. Builds the
# command line (the tests' native reference) and the package (maturin, from PyPI, as the build
# backend), installs it with its Dask extra into a venv under target/, and runs the tests.
# Exits non-zero when anything fails or no test ran.
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD

# The reference binary: target/release/lanecast (already there when .ci/run built it).
cargo build --release --bin lanecast
export LANECAST_BIN="$root/target/release/lanecast"

venv="$root/target/py-venv"
python3 -m venv "$venv"
"$venv/bin/python" -m pip install --quiet --upgrade pip
# The extension builds in its own target folder, so it never waits on the main build's lock.
CARGO_TARGET_DIR="$root/target/python" "$venv/bin/python" -m pip install --quiet "./python[dask]" pytest

# The binding crate lints clean (it is not a default member, so the root's clippy skips it;
# --no-deps: the library is linted by .ci/run).
PYO3_PYTHON="$venv/bin/python" CARGO_TARGET_DIR="$root/target/python" \
    cargo clippy -p lanecast-python --release --no-deps -- -D warnings

# The tests import the installed package, not the source folder.
cd "$root/python/tests"
"$venv/bin/python" -c "import lanecast, lanecast.dask; print('lanecast', lanecast.__file__)"
"$venv/bin/python" -m pytest -p no:cacheprovider -q "$root/python/tests"
