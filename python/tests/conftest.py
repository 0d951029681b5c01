"""Shared fixtures: the repository's scenes and the native command line as the reference.

The reference for every render is the `lanecast` binary of this repository (the same engine
through the command line): set LANECAST_BIN to it, or build it with `cargo build --release`
(target/release/lanecast is looked for first, then target/python/release/lanecast).
"""

import os
import pathlib
import subprocess

import numpy as np
import pytest

REPO = pathlib.Path(__file__).resolve().parents[2]
SCENES = REPO / "scenes"
SEED_SCENES = [SCENES / f"scene{i}.sc" for i in range(1, 8)]
MESH_SCENES = [SCENES / "bunny.sc", SCENES / "teapot.sc"]


def _cli_path():
    env = os.environ.get("LANECAST_BIN")
    if env:
        return pathlib.Path(env)
    for p in (REPO / "target/release/lanecast", REPO / "target/python/release/lanecast"):
        if p.exists():
            return p
    return None


@pytest.fixture(scope="session")
def cli():
    """Runs the native lanecast command line on a scene; returns (ids, depth) from its .npy
    files, and the image from its BMP when asked."""
    exe = _cli_path()
    if exe is None or not exe.exists():
        pytest.fail(
            "the native reference is missing: set LANECAST_BIN or run `cargo build --release` "
            "at the repository root"
        )

    def run(scene, tmp, size=(160, 120), args=(), image=False):
        tmp = pathlib.Path(tmp)
        ids, depth, bmp = tmp / "ids.npy", tmp / "depth.npy", tmp / "img.bmp"
        cmd = [str(exe), "-i", str(scene), "-size", f"{size[0]}x{size[1]}",
               "--ids", str(ids), "--depth", str(depth), "-o", str(bmp), *map(str, args)]
        subprocess.run(cmd, check=True, capture_output=True)
        out = (np.load(ids), np.load(depth))
        if image:
            out = out + (read_bmp(bmp),)
        return out

    run.exe = exe
    return run


def read_bmp(path):
    """A 24-bit uncompressed BMP as uint8 (H, W, 3) RGB, row 0 at the top."""
    b = pathlib.Path(path).read_bytes()
    assert b[:2] == b"BM"
    off = int.from_bytes(b[10:14], "little")
    w = int.from_bytes(b[18:22], "little", signed=True)
    h = int.from_bytes(b[22:26], "little", signed=True)
    bpp = int.from_bytes(b[28:30], "little")
    assert bpp == 24, bpp
    stride = (w * 3 + 3) // 4 * 4
    rows = np.frombuffer(b, np.uint8, count=stride * abs(h), offset=off).reshape(abs(h), stride)
    img = rows[:, : w * 3].reshape(abs(h), w, 3)[:, :, ::-1]
    return img[::-1] if h > 0 else img


def same_bits(a, b):
    """Equal shape, dtype and bytes (so +inf and -0.0 count, as a file comparison would)."""
    a, b = np.asarray(a), np.asarray(b)
    return a.shape == b.shape and a.dtype == b.dtype and a.tobytes() == b.tobytes()
