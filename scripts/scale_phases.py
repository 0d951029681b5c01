#!/usr/bin/env python3
"""The whole command and each of its phases against primitive count, lanecast and Embree 3.

Usage: python3 scripts/scale_phases.py [--rounds R] [--quick]

What it measures, at 1920x1080, on 1 and 2 threads:
- scenes: the shared scaling scenes (../shared/anchors/gen_scenes.py --out target/scale:
  spheres_N.sc and triangles_N.sc, N = 16, 256, 4096, 65536) and the armadillo mesh
  midpoint-subdivided L = 0, 1, 2, 3 times (scripts/subdivide.py -> target/scale/armadillo_L.obj,
  52,000 / 208,000 / 832,000 / 3,328,000 triangles; target/scale/armadillo_L.sc has the camera of
  scenes/armadillo.sc). Existing files are kept, not regenerated.
- lanecast: `target/release/lanecast -i SCENE -o OUT.png -size 1920x1080 --threads T --stats S.json`.
  Whole = wall time of the process (time.perf_counter around the subprocess: start, parse, setup,
  render, shade, PNG write, exit); phases from the JSON's `phases_s`; `peak_rss_bytes`.
- Embree: the reference caster (../shared/anchors/embree, built into target/embree/) with
  `--size 1920x1080 --api 8 --threads T --repeat 1`: whole wall time measured the same way, and its
  `build_ms` (BVH build) and `render_ms`. It parses the scene itself and writes no image: whole
  minus build minus render is its 'parse+other'.
- The two programs alternate (which one goes first alternates too), R rounds (default 3); the
  table gives medians. The scene files are read once before timing so both find them cached.
--quick: 1 round, N = 256 and 65536 only, armadillo levels 0 and 3 (still writes the 3.3M mesh,
  ~134 MB, once).

Below the table, for the 3.3M-triangle armadillo: lanecast's whole command at 2 threads, its whole
time at 1 thread over 2 threads, and its peak resident memory per triangle.

Builds the Embree caster and lanecast (`cargo build --release`) first. Needs ../shared/anchors and
Debian's libembree-dev (`apt-get install -y libembree-dev`). Writes docs/perf/scale-phases.md
(table, armadillo figures) and docs/perf/scale-phases.svg (log-log chart, hand-written SVG).
"""
import argparse
import json
import math
import os
import pathlib
import statistics
import subprocess
import sys
import tempfile
import time
import xml.etree.ElementTree as ET

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
import vs_embree  # noqa: E402  (the shared build step, sh() and cpu())
from vs_embree import cpu, sh  # noqa: E402

ROOT = pathlib.Path(__file__).resolve().parent.parent
SHARED = ROOT.parent / "shared" / "anchors"
LANECAST = ROOT / "target" / "release" / "lanecast"
EMBREE = ROOT / "target" / "embree" / "embree_cast"
SCALE = ROOT / "target" / "scale"
OUT = ROOT / "docs" / "perf"
SIZE = "1920x1080"
THREADS = (1, 2)
ARMADILLO = ROOT / "scenes" / "meshes" / "armadillo.obj"
ARMADILLO_CAMERA = "camera eye 60 60 -330 look 0 22 0 up 0 1 0 fov 40"  # as scenes/armadillo.sc


def build(ns, levels):
    # vs_embree.build: the Embree caster, lanecast, the shared scaling scenes
    vs_embree.build()
    for level in levels:
        obj = SCALE / f"armadillo_{level}.obj"
        if not obj.exists():
            print(f"writing {obj.relative_to(ROOT)} ...", file=sys.stderr)
            sh([sys.executable, str(ROOT / "scripts" / "subdivide.py"), str(ARMADILLO), str(obj), str(level)])
        sc = SCALE / f"armadillo_{level}.sc"
        text = (f"# The armadillo midpoint-subdivided {level} times (scripts/subdivide.py), "
                f"seen as scenes/armadillo.sc.\n{ARMADILLO_CAMERA}\nmesh armadillo_{level}.obj\n")
        if not sc.exists() or sc.read_text() != text:
            sc.write_text(text)


def cases(quick):
    ns = [256, 65536] if quick else [16, 256, 4096, 65536]
    levels = [0, 3] if quick else [0, 1, 2, 3]
    out = [(f"{k}_{n}", k, SCALE / f"{k}_{n}.sc") for k in ("spheres", "triangles") for n in ns]
    out += [(f"armadillo_{l}", "armadillo", SCALE / f"armadillo_{l}.sc") for l in levels]
    return ns, levels, out


def warm(scene):
    """Reads the scene and the meshes it names once, so the first timed run finds them cached."""
    with open(scene, "rb") as f:
        data = f.read()
    for line in data.decode(errors="replace").splitlines():
        parts = line.split()
        if len(parts) == 2 and parts[0] == "mesh":
            with open(scene.parent / parts[1], "rb") as m:
                while m.read(1 << 24):
                    pass


def timed(cmd):
    t = time.perf_counter()
    p = subprocess.run(cmd, capture_output=True, text=True)
    wall = time.perf_counter() - t
    if p.returncode != 0:
        msg = (p.stderr.strip().splitlines() or [f"exit {p.returncode}"])[-1]
        raise RuntimeError(f"{pathlib.Path(cmd[0]).name} exit {p.returncode}: {msg}")
    return wall, p.stdout


def run_embree(scene, threads):
    wall, out = timed([str(EMBREE), str(scene), "--size", SIZE, "--api", "8", "--threads", str(threads),
                       "--repeat", "1"])
    kv = dict(line.split("=", 1) for line in out.split() if "=" in line)
    build_s, render_s = float(kv["build_ms"]) / 1e3, float(kv["render_ms"]) / 1e3
    return {"whole": wall, "build": build_s, "render": render_s, "other": wall - build_s - render_s,
            "prims": int(kv["prims"])}


def run_lanecast(scene, threads, tmp):
    stats = tmp / "stats.json"
    wall, _ = timed([str(LANECAST), "-i", str(scene), "-o", str(tmp / "out.png"), "-size", SIZE,
                     "--threads", str(threads), "--stats", str(stats)])
    s = json.loads(stats.read_text())
    ph = s["phases_s"]
    return {"whole": wall, "parse": ph["parse"], "setup": ph["setup"], "render": ph["render"],
            "shade_write": ph["shade"] + ph["write"], "peak": s["peak_rss_bytes"] or float("nan"),
            "prims": sum(s["primitives"].values())}


def median_of(runs):
    if not runs:
        return None
    return {k: statistics.median(r[k] for r in runs) for k in runs[0]}


def measure(name, kind, scene, threads, rounds, tmp):
    e, l, errors = [], [], []
    for i in range(rounds):
        order = ("embree", "lanecast") if i % 2 == 0 else ("lanecast", "embree")
        for prog in order:
            try:
                if prog == "embree":
                    e.append(run_embree(scene, threads))
                else:
                    l.append(run_lanecast(scene, threads, tmp))
            except RuntimeError as err:
                errors.append(f"{name}, {threads} thread(s): {err}")
    le, em = median_of(l), median_of(e)
    prims = (le or em or {"prims": 0})["prims"]
    print(f"{name:>14} t{threads}: lanecast {le['whole'] if le else float('nan'):.3f} s, "
          f"Embree {em['whole'] if em else float('nan'):.3f} s", file=sys.stderr)
    return {"name": name, "kind": kind, "threads": threads, "prims": int(prims), "l": le, "e": em,
            "errors": errors}




def f3(v):
    return "n/a" if v is None or (isinstance(v, float) and math.isnan(v)) else f"{v:.4f}"


def table(rows):
    out = ["| scene | primitives | threads | lanecast whole s | parse | setup | render | shade+write | "
           "peak MiB | bytes/primitive | Embree whole s | build | render | parse+other | "
           "ratio Embree/lanecast whole |",
           "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for r in rows:
        l, e = r["l"], r["e"]
        lc = ([f3(l["whole"]), f3(l["parse"]), f3(l["setup"]), f3(l["render"]), f3(l["shade_write"]),
               f"{l['peak'] / 2**20:.0f}", f"{l['peak'] / max(r['prims'], 1):,.0f}"] if l else ["failed"] + [""] * 6)
        ec = [f3(e["whole"]), f3(e["build"]), f3(e["render"]), f3(e["other"])] if e else ["failed"] + [""] * 3
        ratio = f"{e['whole'] / l['whole']:.2f}x" if l and e else "n/a"
        out.append(f"| {r['name']} | {r['prims']:,} | {r['threads']} | " + " | ".join(lc + ec) + f" | {ratio} |")
    return "\n".join(out)


def largest(rows):
    """lanecast's figures for the largest mesh (armadillo level 3)."""
    big = {r["threads"]: r for r in rows if r["name"] == "armadillo_3" and r["l"]}
    if 1 not in big or 2 not in big:
        return ["- armadillo level 3 (3.3M triangles): no lanecast measurement on both 1 and 2 threads"]
    w1, w2 = big[1]["l"]["whole"], big[2]["l"]["whole"]
    tris = big[2]["prims"]
    bpt = max(big[t]["l"]["peak"] for t in (1, 2)) / tris
    return [f"- armadillo level 3 ({tris:,} triangles): lanecast whole command at 2 threads {w2:.3f} s",
            f"- 1-thread / 2-thread whole time: {w1:.3f} s / {w2:.3f} s = {w1 / w2:.2f}x",
            f"- peak resident memory per triangle (larger of 1 and 2 threads): {bpt:.0f} B"]


# Series of the chart: (label, program, key, colour, stroke width, dash).
SERIES = [("lanecast whole", "l", "whole", "#d62728", 3, ""),
          ("lanecast parse", "l", "parse", "#ff7f0e", 1.5, "6,3"),
          ("lanecast setup", "l", "setup", "#e377c2", 1.5, "2,3"),
          ("lanecast render", "l", "render", "#8c564b", 1.5, "10,3,2,3"),
          ("Embree whole", "e", "whole", "#1f77b4", 3, ""),
          ("Embree build", "e", "build", "#17becf", 1.5, "6,3"),
          ("Embree render", "e", "render", "#2ca02c", 1.5, "10,3,2,3")]
FLOOR_S = 1e-5  # smaller values (e.g. a 16-primitive setup) are drawn on the bottom axis


def chart(rows, path):
    """Log-log seconds against primitives, 2 threads: one line per series and scene family
    (random triangles: filled circles; armadillo levels: squares; random spheres: open circles)."""
    W, H, L, R, T, B = 860, 520, 70, 200, 40, 56
    pts = [r for r in rows if r["threads"] == 2 and r["prims"] > 0]
    vals = [r[p][k] for r in pts for _, p, k, *_ in SERIES if r[p] and r[p][k] > 0]
    xs = [r["prims"] for r in pts]
    if not vals or not xs:
        return
    x0, x1 = math.floor(math.log10(min(xs))), math.ceil(math.log10(max(xs)))
    y0 = math.floor(math.log10(max(min(vals), FLOOR_S)))
    y1 = math.ceil(math.log10(max(vals)))
    X = lambda v: L + (math.log10(v) - x0) / (x1 - x0) * (W - L - R)
    Y = lambda v: H - B - (math.log10(max(v, 10 ** y0)) - y0) / (y1 - y0) * (H - T - B)
    s = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{W}" height="{H}" font-family="sans-serif" font-size="12">',
         f'<rect width="{W}" height="{H}" fill="white"/>',
         f'<text x="{(L + W - R) / 2}" y="20" text-anchor="middle" font-size="14">'
         f'lanecast and Embree 3, whole command and phases, {SIZE}, 2 threads</text>']
    for e in range(y0, y1 + 1):
        y = Y(10 ** e)
        s.append(f'<line x1="{L}" y1="{y:.1f}" x2="{W - R}" y2="{y:.1f}" stroke="#ddd"/>')
        s.append(f'<text x="{L - 6}" y="{y + 4:.1f}" text-anchor="end">{10 ** e:g}</text>')
    for e in range(x0, x1 + 1):
        x = X(10 ** e)
        s.append(f'<line x1="{x:.1f}" y1="{T}" x2="{x:.1f}" y2="{H - B}" stroke="#eee"/>')
        label = f"{10 ** e:,}" if e < 6 else f"{10 ** (e - 6):g}M"
        s.append(f'<text x="{x:.1f}" y="{H - B + 16}" text-anchor="middle">{label}</text>')
    s.append(f'<rect x="{L}" y="{T}" width="{W - L - R}" height="{H - T - B}" fill="none" stroke="#999"/>')
    s.append(f'<text x="{(L + W - R) / 2}" y="{H - 14}" text-anchor="middle">primitives (log)</text>')
    s.append(f'<text transform="translate(18,{(T + H - B) / 2}) rotate(-90)" text-anchor="middle">seconds (log)</text>')
    families = [("triangles", "circle"), ("armadillo", "square"), ("spheres", "open")]
    for label, p, k, colour, width, dash in SERIES:
        for fam, marker in families:
            ser = sorted((r["prims"], r[p][k]) for r in pts if r["kind"] == fam and r[p])
            if not ser:
                continue
            d = " ".join(f"{X(n):.1f},{Y(v):.1f}" for n, v in ser)
            op = ' stroke-opacity="0.55"' if fam == "spheres" else ""
            s.append(f'<polyline points="{d}" fill="none" stroke="{colour}" stroke-width="{width}" '
                     f'stroke-dasharray="{dash}"{op}/>')
            for n, v in ser:
                cx, cy = X(n), Y(v)
                if marker == "square":
                    s.append(f'<rect x="{cx - 3.5:.1f}" y="{cy - 3.5:.1f}" width="7" height="7" fill="{colour}"/>')
                elif marker == "open":
                    s.append(f'<circle cx="{cx:.1f}" cy="{cy:.1f}" r="3.5" fill="white" stroke="{colour}" stroke-width="1.5"/>')
                else:
                    s.append(f'<circle cx="{cx:.1f}" cy="{cy:.1f}" r="3.5" fill="{colour}"/>')
    lx = W - R + 12
    for i, (label, _, _, colour, width, dash) in enumerate(SERIES):
        ly = T + 8 + i * 20
        s.append(f'<line x1="{lx}" y1="{ly}" x2="{lx + 28}" y2="{ly}" stroke="{colour}" stroke-width="{width}" '
                 f'stroke-dasharray="{dash}"/>')
        s.append(f'<text x="{lx + 34}" y="{ly + 4}">{label}</text>')
    ly = T + 8 + len(SERIES) * 20 + 14
    s.append(f'<circle cx="{lx + 14}" cy="{ly}" r="3.5" fill="#555"/>')
    s.append(f'<text x="{lx + 34}" y="{ly + 4}">random triangles</text>')
    s.append(f'<rect x="{lx + 10.5}" y="{ly + 20 - 3.5}" width="7" height="7" fill="#555"/>')
    s.append(f'<text x="{lx + 34}" y="{ly + 24}">armadillo, subdivided</text>')
    s.append(f'<circle cx="{lx + 14}" cy="{ly + 40}" r="3.5" fill="white" stroke="#555" stroke-width="1.5"/>')
    s.append(f'<text x="{lx + 34}" y="{ly + 44}">random spheres</text>')
    s.append(f'<text x="{lx}" y="{ly + 68}" font-size="10">values under {FLOOR_S:g} s</text>')
    s.append(f'<text x="{lx}" y="{ly + 80}" font-size="10">sit on the bottom axis</text>')
    s.append("</svg>")
    text = "\n".join(s) + "\n"
    ET.fromstring(text)  # well-formed, or this raises
    path.write_text(text)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--rounds", type=int, default=3, help="alternating rounds per case (median taken)")
    ap.add_argument("--quick", action="store_true", help="1 round; N = 256, 65536; armadillo levels 0, 3")
    a = ap.parse_args()
    rounds = 1 if a.quick else a.rounds
    ns, levels, todo = cases(a.quick)
    build(ns, levels)
    rows, errors = [], []
    with tempfile.TemporaryDirectory() as t:
        tmp = pathlib.Path(t)
        for name, kind, scene in todo:
            warm(scene)
            for th in THREADS:
                r = measure(name, kind, scene, th, rounds, tmp)
                rows.append(r)
                errors += r["errors"]
    command = "python3 scripts/scale_phases.py" + "".join(f" {x}" for x in sys.argv[1:])
    lines = ["# Whole command and phases against primitive count: lanecast and Embree 3", "",
             f"Measured on {cpu()}, {os.cpu_count()} cores, by `{command}`: {SIZE}, "
             f"median of {rounds} alternating round(s).", "",
             "- lanecast: `lanecast -i SCENE -o OUT.png -size 1920x1080 --threads T --stats S.json`; whole = "
             "wall time of the process (start to exit, PNG written); parse, setup, render, shade+write from "
             "`phases_s`; peak = `peak_rss_bytes`.",
             "- Embree: `embree_cast SCENE --size 1920x1080 --api 8 --threads T --repeat 1` (writes no image); "
             "whole = wall time of the process; build = `build_ms`, render = `render_ms`; "
             "parse+other = whole - build - render.",
             "- Scenes: spheres_N / triangles_N from ../shared/anchors/gen_scenes.py; armadillo_L = "
             "scenes/meshes/armadillo.obj midpoint-subdivided L times (scripts/subdivide.py), camera of "
             "scenes/armadillo.sc.", "",
             table(rows), "",
             "### armadillo level 3", ""] + largest(rows)
    if errors:
        lines += ["", "### Failed runs", ""] + [f"- {x}" for x in errors]
    lines += ["", "![seconds against primitives, whole command and phases](scale-phases.svg)", ""]
    OUT.mkdir(parents=True, exist_ok=True)
    (OUT / "scale-phases.md").write_text("\n".join(lines))
    chart(rows, OUT / "scale-phases.svg")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
