#!/usr/bin/env python3
"""Alternated render timings of lanecast builds, for comparisons docs/performance.md and docs/precision.md quote.

Each BUILD is a lanecast binary, optionally with `:PRECISION` (auto, f32, f64). Every round
runs every build on every scene in turn, one thread,
`lanecast -i SCENE -size WxH --threads 1 --repeat R [--precision P] --stats S.json`,
and keeps the least `render_best_s` over the rounds, so the machine's noise falls on all
builds alike. Scenes named `K_N` are read from target/scale/ (written by
`python3 scripts/vs_embree.py`), others are paths. Where a build has both K_256 and K_65536,
the growth from N = 256 to 65,536 is printed too.

    python3 scripts/alternate.py target/release/lanecast:f32 target/release/lanecast:auto \
        --scenes spheres_256 spheres_65536 triangles_256 triangles_65536
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile

from scale_scenes import scene_path

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("builds", nargs="+", help="BIN or BIN:PRECISION")
    ap.add_argument("--scenes", nargs="+", required=True)
    ap.add_argument("--size", default="1280x720")
    ap.add_argument("--rounds", type=int, default=5)
    ap.add_argument("--repeat", type=int, default=20)
    a = ap.parse_args()
    builds = [(b.split(":")[0], b.split(":")[1] if ":" in b else None) for b in a.builds]
    for b, _ in builds:
        if not os.access(b, os.X_OK):
            sys.exit(f"{b}: no such executable (build one with `cargo build --release`: "
                     "target/release/lanecast)")
    for sc in a.scenes:
        scene_path(sc)  # fails early, naming a missing scene
    best = {}
    with tempfile.TemporaryDirectory() as tmp:
        stats, image = os.path.join(tmp, "s.json"), os.path.join(tmp, "x.png")
        for _ in range(a.rounds):
            for b, p in builds:
                for sc in a.scenes:
                    cmd = [b, "-i", scene_path(sc), "-size", a.size, "--threads", "1",
                           "--repeat", str(a.repeat), "--stats", stats, "-o", image]
                    if p:
                        cmd += ["--precision", p]
                    subprocess.run(cmd, check=True, capture_output=True)
                    t = json.load(open(stats))["render_best_s"]
                    key = (b, p, sc)
                    best[key] = min(best.get(key, float("inf")), t)
    for b, p in builds:
        line = f"{b}{':' + p if p else ''}: " + "  ".join(
            f"{sc} {best[(b, p, sc)] * 1e3:.2f} ms" for sc in a.scenes)
        for k in ("spheres", "triangles"):
            small, big = (b, p, f"{k}_256"), (b, p, f"{k}_65536")
            if small in best and big in best:
                line += f"  {k} growth {best[big] / best[small]:.2f}x"
        print(line)


if __name__ == "__main__":
    main()
