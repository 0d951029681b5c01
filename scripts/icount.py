#!/usr/bin/env python3
"""Instructions per frame of `--precision f32` and `--precision auto`, counted by valgrind.

On a shared machine, wall-clock ratios of two renderers move by several percent between runs;
instruction counts do not. This script builds `examples/frames.rs` for AVX2
(`-C target-cpu=x86-64-v3`, into target/icount: valgrind 3.19 decodes no AVX-512, and the
lanes are f32x8 either way) in the `profiling` profile (the release build with line tables,
so `cg_annotate` can name source lines), runs it under `valgrind --tool=cachegrind` for 1 and for
FRAMES + 1 frames of each scene and precision (packet kernel, automatic acceleration, one
thread, 1280x720), and prints the difference per frame: the render alone, without setup.
Instructions are not time: memory stalls and latency do not show. Speed is measured by
`cargo bench --bench precision`; this shows where auto's own work goes and how much of it a
change removed.

    python3 scripts/icount.py scenes/scene7.sc spheres_256 [--frames 3] [--cache]

With `--cache`, valgrind also simulates a 1 MiB 8-way last-level cache (about this machine's
L2 per core) and the table adds its read misses per frame (`DLmr`): cache misses that
instruction counts do not show.

Scenes named `K_N` are read from target/scale/ (written by `python3 scripts/vs_embree.py`).
"""
import argparse
import os
import shutil
import subprocess
import sys
import tempfile

from scale_scenes import scene_path

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
TARGET = os.path.join(ROOT, "target", "icount")


def counts(scene, precision, frames, tmp, cache):
    """Instructions and (with `cache`) last-level read misses of the whole run."""
    out = os.path.join(tmp, "cg.out")
    exe = os.path.join(TARGET, "profiling", "examples", "frames")
    sim = ["--cache-sim=yes", "--LL=1048576,8,64"] if cache else ["--cache-sim=no"]
    subprocess.run(
        ["valgrind", "--tool=cachegrind", *sim, f"--cachegrind-out-file={out}",
         exe, scene, precision, str(frames)],
        check=True, capture_output=True)
    events = None
    with open(out) as f:
        for line in f:
            if line.startswith("events:"):
                events = line.split()[1:]
            if line.startswith("summary:") and events:
                v = dict(zip(events, map(int, line.split()[1:])))
                return v["Ir"], v.get("DLmr", 0)
    raise SystemExit(f"no summary in valgrind's output for {scene} {precision}")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("scenes", nargs="+")
    ap.add_argument("--frames", type=int, default=3)
    ap.add_argument("--cache", action="store_true", help="also simulate a 1 MiB cache")
    a = ap.parse_args()
    if shutil.which("valgrind") is None:
        sys.exit("valgrind is missing: this script counts instructions with cachegrind "
                 "(Debian: apt-get install -y valgrind)")
    for name in a.scenes:
        scene_path(name)  # fails early, naming a missing scene
    env = dict(os.environ, CARGO_TARGET_DIR=TARGET, RUSTFLAGS="-C target-cpu=x86-64-v3")
    subprocess.run(["cargo", "build", "--profile", "profiling", "--example", "frames"],
                   cwd=ROOT, env=env, check=True)
    head = "| scene | f32 M instr / frame | auto M instr / frame | auto over f32 |"
    rule = "|---|---:|---:|---:|"
    if a.cache:
        head += " f32 LL misses / frame | auto LL misses / frame |"
        rule += "---:|---:|"
    print(head)
    print(rule)
    with tempfile.TemporaryDirectory() as tmp:
        for name in a.scenes:
            path = scene_path(name)
            per = {}
            for p in ("f32", "auto"):
                one = counts(path, p, 1, tmp, a.cache)
                many = counts(path, p, a.frames + 1, tmp, a.cache)
                per[p] = [(m - o) / a.frames for m, o in zip(many, one)]
            label = os.path.splitext(os.path.basename(path))[0]
            row = (f"| {label} | {per['f32'][0] / 1e6:.2f} | {per['auto'][0] / 1e6:.2f} | "
                   f"{100 * (per['auto'][0] / per['f32'][0] - 1):+.1f}% |")
            if a.cache:
                row += f" {per['f32'][1] / 1e3:.1f}k | {per['auto'][1] / 1e3:.1f}k |"
            print(row)


if __name__ == "__main__":
    main()
