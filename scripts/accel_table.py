#!/usr/bin/env python3
"""docs/performance.md's acceleration table: best render time of none / tiles / bvh, one thread.

    python3 scripts/accel_table.py [--rounds R]

Builds lanecast (`cargo build --release`), writes the shared scaling scenes into target/scale/
(needs ../shared/anchors/gen_scenes.py), then for every scene runs
`lanecast -i SCENE -size 1920x1080 --threads 1 --repeat 7 --accel A --stats S.json` for the
three accelerations in turn, R rounds (default 3), and prints a Markdown table of the median
over rounds of each run's best render (ms), and the setup phase of tiles and bvh. `none` is
skipped past 4,096 primitives (seconds per frame).
"""
import argparse
import json
import pathlib
import statistics
import subprocess
import sys
import tempfile

ROOT = pathlib.Path(__file__).resolve().parent.parent
LANECAST = ROOT / "target" / "release" / "lanecast"
SCALE = ROOT / "target" / "scale"
SCENES = ([f"scenes/scene{n}.sc" for n in (1, 2, 6, 7)] + ["scenes/bunny.sc", "scenes/armadillo.sc"]
          + [f"target/scale/{k}_{n}.sc" for k in ("spheres", "triangles") for n in (256, 65536)])
ACCELS = ("tiles", "bvh", "none")  # tiles first: its run gives the primitive count


def run(scene, accel, tmp):
    stats = tmp / "s.json"
    subprocess.run([str(LANECAST), "-i", str(ROOT / scene), "-o", str(tmp / "o.bmp"), "-size", "1920x1080",
                    "--threads", "1", "--repeat", "7", "--accel", accel, "--stats", str(stats)],
                   check=True, capture_output=True)
    s = json.loads(stats.read_text())
    return s["render_best_s"] * 1e3, s["phases_s"]["setup"] * 1e3, sum(s["primitives"].values())


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--rounds", type=int, default=3)
    a = ap.parse_args()
    subprocess.run(["cargo", "build", "--release"], cwd=ROOT, check=True, capture_output=True)
    SCALE.mkdir(parents=True, exist_ok=True)
    gen = ROOT.parent / "shared" / "anchors" / "gen_scenes.py"
    if not gen.exists():
        sys.exit(f"{gen} is missing: the scaling scenes come from the shared anchors")
    subprocess.run([sys.executable, str(gen), "--out", str(SCALE)], check=True, capture_output=True)
    cpu = next((l.split(":", 1)[1].strip() for l in open("/proc/cpuinfo") if l.startswith("model name")), "?")
    print(f"Best render of 7, median of {a.rounds} rounds, 1 thread, 1920x1080, ms; {cpu}.\n")
    print("| scene | primitives | none | tiles | bvh | setup tiles | setup bvh |")
    print("|---|---:|---:|---:|---:|---:|---:|")
    with tempfile.TemporaryDirectory() as t:
        tmp = pathlib.Path(t)
        for scene in SCENES:
            res = {acc: [] for acc in ACCELS}
            prims = 0
            for _ in range(a.rounds):
                for acc in ACCELS:
                    if acc == "none" and prims > 4096:
                        continue
                    r, su, prims = run(scene, acc, tmp)
                    res[acc].append((r, su))
            med = {k: (statistics.median(x for x, _ in v), statistics.median(y for _, y in v)) if v else None
                   for k, v in res.items()}
            cell = lambda k, i: f"{med[k][i]:.1f}" if med[k] else "-"
            name = pathlib.Path(scene).stem
            print(f"| {name} | {prims:,} | {cell('none', 0)} | {cell('tiles', 0)} | {cell('bvh', 0)} "
                  f"| {cell('tiles', 1)} | {cell('bvh', 1)} |", flush=True)


if __name__ == "__main__":
    main()
