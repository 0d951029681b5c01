#!/usr/bin/env python3
"""Many views of one scan: lanecast (`--views`) against the Embree 3 caster (`--views`), in one run.

Usage: python3 scripts/views_table.py [--views N] [--rounds R] [--threads T] [--size WxH]
                                      [--levels L ...] [--accel auto|tiles|world]

Needs ../shared/anchors (the Embree caster and orbit_views.py; not part of this repository) and
Debian's libembree-dev (`apt-get install -y libembree-dev`). Builds both programs (as
scripts/vs_embree.py does), writes the armadillo subdivided L times into target/scale/
(scripts/subdivide.py; L = 2 gives 832,000 triangles, 3 gives 3,328,000) with a scene file
beside it, and an orbit of N views (orbit_views.py, the same cameras for both programs). Then,
R rounds, alternating the programs:

- lanecast: `-i SCENE --views FILE -size WxH -o DIR/v%04d.bmp --stats S.json --threads T
  --accel A` (`--accel` applies to the single view below too; default `auto`).
  Per view: setup (the scene prepared for the camera) plus render, from --stats' views.each
  (output encoding excluded); whole: the command's wall time (load, every view, BMP outputs).
- Embree: `embree_cast SCENE --size WxH --views FILE --threads T`. Per view: its
  view_median_ms (ray generation, rtcIntersect8, buffers); whole: build_ms + views_total_ms
  (its file reading excluded: its reader is not Embree; it writes no images).

Prints a markdown table (medians over rounds), then a second table from the same rounds:

- single view, per scan: `lanecast -i SCENE -size WxH -o DIR/one.bmp --threads T`, wall time;
- peak memory, per scan: `peak_rss_bytes` of the many-view run's --stats over the triangles;
- parsing: `examples/parse_speed` (RAYON_NUM_THREADS=T), its OBJ grid read from the page cache
  by `load_obj` and through a `mesh` line (MB/s, the read included).

Per-view cost by thread count needs a machine with more cores: scripts/views_scaling.sh.
"""
import argparse
import json
import os
import pathlib
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import vs_embree  # noqa: E402  (its build() builds both programs)

ROOT = vs_embree.ROOT
SCALE = vs_embree.SCALE


def scan(levels):
    """target/scale/armadillo_L.sc: the shared armadillo subdivided `levels` times."""
    obj = SCALE / f"armadillo_{levels}.obj"
    sc = SCALE / f"armadillo_{levels}.sc"
    if not obj.exists():
        src = ROOT / "scenes" / "meshes" / "armadillo.obj"
        vs_embree.sh([sys.executable, str(ROOT / "scripts" / "subdivide.py"), str(src), str(obj),
                      str(levels)])
    sc.write_text("camera eye 60 60 -330 look 0 22 0 up 0 1 0 fov 40\n"
                  f"mesh {obj.name}\n")
    return sc


def orbit(scene, n, out):
    text = vs_embree.sh([sys.executable, str(vs_embree.SHARED / "orbit_views.py"), str(scene),
                         str(n)]).stdout
    out.write_text(text)
    return out


def lanecast(scene, views, size, threads, tmp, accel):
    frames = tmp / "frames"
    shutil.rmtree(frames, ignore_errors=True)
    frames.mkdir()
    stats = tmp / "s.json"
    t0 = time.perf_counter()
    vs_embree.sh([str(vs_embree.LANECAST), "-i", str(scene), "--views", str(views), "-size", size,
                  "-o", str(frames / "v%04d.bmp"), "--stats", str(stats), "--threads",
                  str(threads), "--accel", accel])
    whole = time.perf_counter() - t0
    s = json.loads(stats.read_text())
    each = [v for v in s["views"] if not v["skipped"]]
    per_view = statistics.median(v["setup_s"] + v["render_s"] for v in each)
    setup = statistics.median(v["setup_s"] for v in each)
    render = statistics.median(v["render_s"] for v in each)
    return {"view": per_view * 1e3, "setup": setup * 1e3, "render": render * 1e3,
            "load": s["phases_s"]["load"] * 1e3, "whole": whole * 1e3,
            "peak": s["peak_rss_bytes"]}


def single(scene, size, threads, tmp, accel):
    """Wall seconds of a one-view run of the scene's own camera, a BMP written."""
    t0 = time.perf_counter()
    vs_embree.sh([str(vs_embree.LANECAST), "-i", str(scene), "-size", size, "-o",
                  str(tmp / "one.bmp"), "--threads", str(threads), "--accel", accel])
    return time.perf_counter() - t0


def parse_speed(threads):
    """MB/s of examples/parse_speed's OBJ lines: load_obj, and the OBJ through a mesh line."""
    exe = ROOT / "target" / "release" / "examples" / "parse_speed"
    out = vs_embree.sh([str(exe)], env={**os.environ, "RAYON_NUM_THREADS": str(threads)}).stdout
    speed = {}
    for line in out.splitlines():
        for key in ("load_obj", "load_scene, mesh line"):
            if line.startswith(key):
                speed[key] = float(line.split()[-2])
    return speed


def embree(scene, views, size, threads):
    out = vs_embree.sh([str(vs_embree.EMBREE), str(scene), "--size", size, "--api", "8",
                        "--threads", str(threads), "--views", str(views)]).stdout
    kv = dict(line.split("=", 1) for line in out.split() if "=" in line)
    build, total = float(kv["build_ms"]), float(kv["views_total_ms"])
    return {"view": float(kv["view_median_ms"]), "build": build, "whole": build + total}


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--views", type=int, default=100)
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--size", default="1920x1080")
    ap.add_argument("--levels", type=int, nargs="+", default=[3])
    ap.add_argument("--accel", default="auto", choices=["auto", "tiles", "world"])
    a = ap.parse_args()
    vs_embree.build()
    cpu = vs_embree.cpu()
    print(f"{cpu}, {os.cpu_count()} cores; {a.threads} threads, {a.size}, {a.views}-view orbit, "
          f"--accel {a.accel}, median of {a.rounds} alternated rounds\n")
    print("| scene | triangles | lanecast per view (setup + render) | Embree per view | ratio "
          "| lanecast whole | Embree build + views | ratio |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|")
    vs_embree.sh(["cargo", "build", "--release", "--example", "parse_speed"], cwd=ROOT)
    others = []
    with tempfile.TemporaryDirectory() as t:
        tmp = pathlib.Path(t)
        for levels in a.levels:
            scene = scan(levels)
            views = orbit(scene, a.views, tmp / "views.txt")
            runs_l, runs_e, singles = [], [], []
            for _ in range(a.rounds):
                runs_l.append(lanecast(scene, views, a.size, a.threads, tmp, a.accel))
                runs_e.append(embree(scene, views, a.size, a.threads))
                singles.append(single(scene, a.size, a.threads, tmp, a.accel))
            med = lambda runs, k: statistics.median(r[k] for r in runs)  # noqa: E731
            lv, ev, lw, ew = med(runs_l, "view"), med(runs_e, "view"), med(runs_l, "whole"), \
                med(runs_e, "whole")
            tris = 52_000 * 4 ** levels
            print(f"| armadillo_{levels} | {tris:,} | {lv:.1f} ms ({med(runs_l, 'setup'):.1f} + "
                  f"{med(runs_l, 'render'):.1f}) | {ev:.1f} ms | {ev / lv:.2f}x | {lw / 1e3:.2f} s "
                  f"| {ew / 1e3:.2f} s | {ew / lw:.2f}x |")
            one = statistics.median(singles)
            peak = max(r["peak"] for r in runs_l) / tris
            others.append((f"armadillo_{levels}: single view, whole command", f"{one:.2f} s"))
            others.append((f"armadillo_{levels}: peak memory of the many-view run",
                           f"{peak:.0f} B a triangle"))
        speeds = [parse_speed(a.threads) for _ in range(a.rounds)]
        for key in ("load_obj", "load_scene, mesh line"):
            mbs = statistics.median(sp[key] for sp in speeds)
            others.append((f"parsing, 78.2 MB OBJ grid ({key})", f"{mbs:.0f} MB/s"))
    print("\n| measure | value |\n|---|---:|")
    for what, value in others:
        print(f"| {what} | {value} |")
    print("\nPer-view cost by thread count: scripts/views_scaling.sh on a machine with more cores.")


if __name__ == "__main__":
    main()
