#!/usr/bin/env python3
"""Many views of one scan, three engines in one run: the world-space BVH spike (lab,
`examples/bvh_spike`, both traversal variants), lanecast's object-order engine (`--accel world`)
and the Embree 3 caster (`--views`).

Usage: python3 scripts/bvh_spike_table.py [--views N] [--rounds R] [--threads T] [--size WxH]
                                          [--levels L ...] [--check K]

Needs what scripts/views_table.py needs (../shared/anchors, libembree-dev). Builds the spike
(`cargo build --release -p lanecast-lab --example bvh_spike`) and both programs (as
scripts/vs_embree.py does), makes the armadillo subdivided L times and an orbit of N views
(views_table.scan and orbit: the same cameras for all three). Then R rounds, alternating:

- the spike: `bvh_spike SCENE --views FILE --size WxH --threads T --variant both`: its build
  (ms, ns and bytes a triangle) and each variant's median ms a view (rays, traversal, frame);
- lanecast: views_table.lanecast with `--accel world` (setup + render a view, from --stats);
- Embree: views_table.embree (its view_median_ms; build_ms).

Prints a markdown table of medians over rounds. With --check K, the spike's first K views are
then compared with the f64 oracle (mismatches in ppm, as `lanecast compare` classes them).
"""
import argparse
import os
import pathlib
import statistics
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import vs_embree  # noqa: E402
import views_table  # noqa: E402

ROOT = vs_embree.ROOT
SPIKE = ROOT / "target" / "release" / "examples" / "bvh_spike"


def kv(line):
    return dict(tok.split("=", 1) for tok in line.split() if "=" in tok)


def spike(scene, views, size, threads, check=0):
    out = vs_embree.sh([str(SPIKE), str(scene), "--views", str(views), "--size", size,
                        "--threads", str(threads), "--variant", "both", "--check",
                        str(check)]).stdout
    r = {"checks": []}
    for line in out.splitlines():
        d = kv(line)
        if "build_ms" in d:
            r["build"] = float(d["build_ms"])
            r["ns_tri"] = float(d["ns_per_tri"])
            r["bytes_tri"] = float(d["bytes_per_tri"])
        elif line.startswith("variant="):
            r[d["variant"]] = float(d["view_median_ms"])
            r[d["variant"] + "_counts"] = d
        elif line.startswith("check "):
            r["checks"].append(d)
    return r


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--views", type=int, default=20)
    ap.add_argument("--rounds", type=int, default=2)
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--size", default="1920x1080")
    ap.add_argument("--levels", type=int, nargs="+", default=[3])
    ap.add_argument("--check", type=int, default=0)
    a = ap.parse_args()
    vs_embree.build()
    vs_embree.sh(["cargo", "build", "--release", "-p", "lanecast-lab", "--example", "bvh_spike"],
                 cwd=ROOT)
    cpu = vs_embree.cpu()
    print(f"{cpu}, {os.cpu_count()} cores; {a.threads} threads, {a.size}, {a.views}-view orbit, "
          f"median of {a.rounds} alternated rounds\n")
    rows, notes = [], []
    with tempfile.TemporaryDirectory() as t:
        tmp = pathlib.Path(t)
        for levels in a.levels:
            scene = views_table.scan(levels)
            views = views_table.orbit(scene, a.views, tmp / "views.txt")
            runs_s, runs_w, runs_e = [], [], []
            for _ in range(a.rounds):
                runs_s.append(spike(scene, views, a.size, a.threads))
                runs_w.append(views_table.lanecast(scene, views, a.size, a.threads, tmp, "world"))
                runs_e.append(views_table.embree(scene, views, a.size, a.threads))
            med = lambda runs, k: statistics.median(r[k] for r in runs)  # noqa: E731
            ev = med(runs_e, "view")
            tris = 52_000 * 4 ** levels
            name = f"armadillo_{levels} ({tris / 1e6:.2f}M)"
            for label, view, build in [
                ("BVH spike, packets", med(runs_s, "packets"), med(runs_s, "build")),
                ("BVH spike, frustum", med(runs_s, "frustum"), med(runs_s, "build")),
                ("`--accel world` (object order)", med(runs_w, "view"), None),
                ("Embree 3, rtcIntersect8", ev, med(runs_e, "build")),
            ]:
                b = "" if build is None else f"{build:.0f} ms"
                rows.append(f"| {name} | {label} | {view:.1f} ms | {ev / view:.2f}x | {b} |")
            notes.append(f"{name}: spike build {med(runs_s, 'ns_tri'):.0f} ns a triangle on "
                         f"{a.threads} threads ({med(runs_s, 'ns_tri') * a.threads:.0f} ns of "
                         f"CPU), {med(runs_s, 'bytes_tri'):.1f} bytes a triangle; `--accel world` "
                         f"setup {med(runs_w, 'setup'):.1f} + render {med(runs_w, 'render'):.1f} "
                         f"ms a view")
            for v in ("packets", "frustum"):
                c = runs_s[-1][v + "_counts"]
                notes.append(f"{name}, {v}: a view visits {float(c['nodes_per_view']):,.0f} "
                             f"nodes, {float(c['leaves_per_view']):,.0f} leaves, sets up "
                             f"{float(c['setups_per_view']):,.0f} triangles and runs "
                             f"{float(c['tests8_per_view']):,.0f} 8-ray tests")
            if a.check:
                for c in spike(scene, views, a.size, a.threads, a.check)["checks"]:
                    notes.append(f"{name}, view {c['view']}, {c['variant']}: mismatches "
                                 f"{c['mismatch_ppm']} ppm (ties {c['ties_ppm']}, edge band "
                                 f"{c['edges_ppm']}, unexcused {c['unexcused_ppm']}), depth "
                                 f"error max {c['depth_rel_max']}, p99 {c['depth_rel_p99']}")
    print("| scene | engine | per view | Embree's / this | build once |")
    print("|---|---|---:|---:|---:|")
    print("\n".join(rows))
    print()
    for n in notes:
        print(f"- {n}")


if __name__ == "__main__":
    main()
