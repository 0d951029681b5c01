#!/usr/bin/env python3
"""lanecast against the Embree 3 reference caster, side by side, in one run.

Usage: python3 scripts/vs_embree.py [--rounds R] [--repeat K] [--quick]

Needs ../shared/anchors (the Embree caster's source and the scaling-scene generator; not part of
this repository) and Debian's libembree-dev (`apt-get install -y libembree-dev`). Builds the
caster into target/embree/, lanecast with `cargo build --release`, writes the scaling scenes into
target/scale/, then for every case alternates the two programs R times (so machine noise hits
both alike). Each run renders K times and reports its best render phase: Embree's `render_ms`
(ray generation + rtcIntersect8 on 4x2 blocks + id/depth buffers, threads started and joined;
not its BVH build), lanecast's `render_best_s` from --stats (ray generation + packet kernel +
id/depth buffers, rayon pool already started; not its setup phase, where the default `tiles`
acceleration bins the primitives). The table gives the median over rounds of those bests, as
Mrays/s, and the ratio lanecast / Embree.

The report, on 1 and 2 threads:
- seed scenes 1-7, 1920x1080; scaling scenes (spheres_N, triangles_N, N = 16, 256, 4096,
  65,536), 1280x720; meshes (bunny, teapot, armadillo), 1920x1080: one table each, a line per
  case and thread count;
- growth, 1 thread, 1280x720: render time at N = 65,536 over N = 256, for spheres and for
  triangles, lanecast's and Embree's;
- a 7680x4320 render of scene2: lanecast's peak resident memory, in MiB and bytes a pixel;
- `lanecast -i scenes/scene2.sc -size 1920x1080` (all threads, PNG): its render, shade and write
  phases and the PNG's size.
--quick: 1 round, scaling scenes at N = 256 and 65,536 only.

Writes docs/perf/vs-embree.md (the report) and docs/perf/scaling.svg (log-log chart).
"""
import argparse
import json
import math
import os
import pathlib
import shutil
import statistics
import subprocess
import sys
import tempfile

ROOT = pathlib.Path(__file__).resolve().parent.parent
SHARED = ROOT.parent / "shared" / "anchors"
LANECAST = ROOT / "target" / "release" / "lanecast"
EMBREE = ROOT / "target" / "embree" / "embree_cast"
SCALE = ROOT / "target" / "scale"
OUT = ROOT / "docs" / "perf"
MESHES = ["bunny", "teapot", "armadillo"]


def sh(cmd, **kw):
    return subprocess.run(cmd, check=True, capture_output=True, text=True, **kw)


def build():
    if not SHARED.is_dir():
        sys.exit(f"{SHARED} is missing: this comparison needs the Embree reference caster and the "
                 "scaling-scene generator, which live beside the checkout (../shared/anchors), "
                 "not in this repository")
    if shutil.which("g++") is None:
        sys.exit("g++ is missing: the Embree reference caster is built with g++")
    dst = ROOT / "target" / "embree"
    dst.mkdir(parents=True, exist_ok=True)
    for f in ["build.sh", "embree_cast.cpp"]:
        shutil.copy(SHARED / "embree" / f, dst / f)
    try:
        sh(["bash", str(dst / "build.sh")])
    except subprocess.CalledProcessError as e:
        sys.exit("building the Embree reference caster failed; it needs Embree 3 "
                 "(Debian: apt-get install -y libembree-dev):\n" + (e.stderr or "").strip()[-2000:])
    sh(["cargo", "build", "--release"], cwd=ROOT)
    SCALE.mkdir(parents=True, exist_ok=True)
    sh([sys.executable, str(SHARED / "gen_scenes.py"), "--out", str(SCALE)])


def embree(scene, size, threads, repeat):
    out = sh([str(EMBREE), str(scene), "--size", size, "--api", "8", "--threads", str(threads),
              "--repeat", str(repeat)]).stdout
    kv = dict(line.split("=", 1) for line in out.split() if "=" in line)
    return float(kv["render_ms"]) / 1e3


def lanecast(scene, size, threads, repeat, tmp):
    stats = tmp / "stats.json"
    sh([str(LANECAST), "-i", str(scene), "-o", str(tmp / "out.bmp"), "-size", size,
        "--threads", str(threads), "--repeat", str(repeat), "--stats", str(stats)])
    s = json.loads(stats.read_text())
    return s["render_best_s"], s


def cases(quick):
    seeds = [(f"scene{n}", ROOT / "scenes" / f"scene{n}.sc", "1920x1080") for n in range(1, 8)]
    ns = [256, 65536] if quick else [16, 256, 4096, 65536]
    scaling = [(f"{k}_{n}", SCALE / f"{k}_{n}.sc", "1280x720") for k in ["spheres", "triangles"] for n in ns]
    meshes = [(m, ROOT / "scenes" / f"{m}.sc", "1920x1080") for m in MESHES if (ROOT / "scenes" / f"{m}.sc").exists()]
    return seeds, scaling, meshes


def measure(name, scene, size, threads, rounds, repeat, tmp):
    e, l = [], []
    info = None
    for _ in range(rounds):
        e.append(embree(scene, size, threads, repeat))
        t, info = lanecast(scene, size, threads, repeat, tmp)
        l.append(t)
    w, h = map(int, size.split("x"))
    em, lm = statistics.median(e), statistics.median(l)
    prims = sum(info["primitives"].values())
    return {"name": name, "size": size, "threads": threads, "prims": prims, "accel": info["accel"],
            "embree_s": em, "lanecast_s": lm, "embree_mrays": w * h / em / 1e6,
            "lanecast_mrays": w * h / lm / 1e6}


def cpu():
    for line in open("/proc/cpuinfo"):
        if line.startswith("model name"):
            return line.split(":", 1)[1].strip()
    return "unknown CPU"


def table(rows):
    """One line per case: Mrays/s of each program and the ratio lanecast / Embree."""
    out = ["| scene | size | prims | threads | accel | Embree Mrays/s | lanecast Mrays/s | ratio |",
           "|---|---|---:|---:|---|---:|---:|---:|"]
    for r in rows:
        ratio = r["lanecast_mrays"] / r["embree_mrays"]
        out.append(f"| {r['name']} | {r['size']} | {r['prims']} | {r['threads']} | {r['accel']} | "
                   f"{r['embree_mrays']:.1f} | {r['lanecast_mrays']:.1f} | {ratio:.2f}x |")
    return "\n".join(out)


def chart(rows, path):
    """Log-log render time against primitive count: lanecast and Embree, spheres and triangles."""
    W, H, L, R, T, B = 700, 420, 70, 210, 30, 50
    pts = [r for r in rows if r["threads"] == 1]
    xs = [r["prims"] for r in pts]
    ys = [r[k] * 1e3 for r in pts for k in ("embree_s", "lanecast_s")]
    x0, x1 = math.log10(min(xs)), math.log10(max(xs))
    y0, y1 = math.floor(math.log10(min(ys))), math.ceil(math.log10(max(ys)))
    X = lambda v: L + (math.log10(v) - x0) / (x1 - x0) * (W - L - R)
    Y = lambda v: H - B - (math.log10(v) - y0) / (y1 - y0) * (H - T - B)
    s = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{W}" height="{H}" font-family="sans-serif" font-size="12">',
         f'<rect width="{W}" height="{H}" fill="white"/>']
    for e in range(y0, y1 + 1):
        y = Y(10 ** e)
        s.append(f'<line x1="{L}" y1="{y:.1f}" x2="{W - R}" y2="{y:.1f}" stroke="#ddd"/>')
        s.append(f'<text x="{L - 6}" y="{y + 4:.1f}" text-anchor="end">{10 ** e:g}</text>')
    for n in sorted(set(xs)):
        x = X(n)
        s.append(f'<line x1="{x:.1f}" y1="{T}" x2="{x:.1f}" y2="{H - B}" stroke="#eee"/>')
        s.append(f'<text x="{x:.1f}" y="{H - B + 16}" text-anchor="middle">{n}</text>')
    s.append(f'<text x="{(L + W - R) / 2}" y="{H - 10}" text-anchor="middle">primitives (log)</text>')
    s.append(f'<text transform="translate(16,{(T + H - B) / 2}) rotate(-90)" text-anchor="middle">render time, ms, 1 thread, 1280x720 (log)</text>')
    styles = [("lanecast_s", "spheres", "#d62728", ""), ("lanecast_s", "triangles", "#d62728", "6,3"),
              ("embree_s", "spheres", "#1f77b4", ""), ("embree_s", "triangles", "#1f77b4", "6,3")]
    for i, (key, kind, colour, dash) in enumerate(styles):
        series = sorted((r["prims"], r[key] * 1e3) for r in pts if r["name"].startswith(kind))
        d = " ".join(f"{X(n):.1f},{Y(v):.1f}" for n, v in series)
        s.append(f'<polyline points="{d}" fill="none" stroke="{colour}" stroke-width="2" stroke-dasharray="{dash}"/>')
        for n, v in series:
            s.append(f'<circle cx="{X(n):.1f}" cy="{Y(v):.1f}" r="3" fill="{colour}"/>')
        ly = T + 10 + i * 18
        s.append(f'<line x1="{W - R + 10}" y1="{ly}" x2="{W - R + 34}" y2="{ly}" stroke="{colour}" stroke-width="2" stroke-dasharray="{dash}"/>')
        name = ("lanecast" if key == "lanecast_s" else "Embree 3") + " " + kind
        s.append(f'<text x="{W - R + 40}" y="{ly + 4}">{name}</text>')
    s.append("</svg>")
    path.write_text("\n".join(s) + "\n")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--quick", action="store_true", help="fewer scaling sizes, 1 round")
    a = ap.parse_args()
    rounds = 1 if a.quick else a.rounds
    build()
    seeds, scaling, meshes = cases(a.quick)
    with tempfile.TemporaryDirectory() as t:
        tmp = pathlib.Path(t)
        seed_rows = [measure(n, s, z, th, rounds, a.repeat, tmp) for th in (1, 2) for n, s, z in seeds]
        scale_rows = [measure(n, s, z, th, rounds, a.repeat, tmp) for th in (1, 2) for n, s, z in scaling]
        mesh_rows = [measure(n, s, z, th, rounds, a.repeat, tmp) for th in (1, 2) for n, s, z in meshes]
        # whole command, scene2 at 1920x1080, PNG written: write phase against render phase
        _, whole = lanecast(ROOT / "scenes" / "scene2.sc", "1920x1080", os.cpu_count(), 1, tmp)
        sh([str(LANECAST), "-i", str(ROOT / "scenes" / "scene2.sc"), "-o", str(tmp / "w.png"),
            "-size", "1920x1080", "--stats", str(tmp / "w.json")])
        whole = json.loads((tmp / "w.json").read_text())
        png_bytes = (tmp / "w.png").stat().st_size
        # memory: a 7680x4320 render
        sh([str(LANECAST), "-i", str(ROOT / "scenes" / "scene2.sc"), "-o", str(tmp / "m.png"),
            "-size", "7680x4320", "--stats", str(tmp / "m.json")])
        mem = json.loads((tmp / "m.json").read_text())
    lines = [f"Measured by `python3 scripts/vs_embree.py` on {cpu()}, {os.cpu_count()} cores; "
             f"median of {rounds} alternating rounds, each the best of {a.repeat} renders; Embree `--api 8`.", ""]
    lines += ["### Seed scenes, 1920x1080", "", table(seed_rows), ""]
    lines += ["### Scaling scenes, 1280x720", "", table(scale_rows), ""]
    if mesh_rows:
        lines += ["### Meshes, 1920x1080", "", table(mesh_rows), ""]
    lines += ["### Growth, 1 thread, 1280x720 (render time at N = 65,536 over N = 256)", ""]
    for kind in ("spheres", "triangles"):
        r = {x["prims"]: x["lanecast_s"] for x in scale_rows if x["threads"] == 1 and x["name"].startswith(kind)}
        e = {x["prims"]: x["embree_s"] for x in scale_rows if x["threads"] == 1 and x["name"].startswith(kind)}
        if 256 in r and 65536 in r:
            g = r[65536] / r[256]
            lines.append(f"- {kind}: lanecast {g:.2f}x; Embree {e[65536] / e[256]:.2f}x")
    px = 7680 * 4320
    peak = mem["peak_rss_bytes"]
    lines += ["", "### Memory and write phase", "",
              f"- 7680x4320 render of scene2: peak resident {peak / 2**20:.0f} MiB = {peak / px:.1f} bytes/pixel",
              f"- `lanecast -i scenes/scene2.sc -size 1920x1080` (all threads, PNG): render "
              f"{whole['phases_s']['render'] * 1e3:.1f} ms, shade {whole['phases_s']['shade'] * 1e3:.1f} ms, "
              f"write {whole['phases_s']['write'] * 1e3:.1f} ms ({png_bytes / 1024:.0f} KiB PNG)",
              "", "![render time against primitive count](scaling.svg)", ""]
    OUT.mkdir(parents=True, exist_ok=True)
    (OUT / "vs-embree.md").write_text("\n".join(lines))
    chart(scale_rows, OUT / "scaling.svg")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
