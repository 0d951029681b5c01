#!/usr/bin/env python3
"""Prints docs/performance.md's packet-against-scalar table from criterion's results of `cargo bench --bench render`.

Reads target/criterion/**/new/{benchmark,estimates}.json (written by the last bench run) and
prints, per seed scene and size, Mrays/s of each kernel on 1 and all threads (mean estimate),
with two ratios: packet / scalar f32 on one thread, and packet on all threads / packet on one
thread.
"""
import json
import pathlib
import platform
import re
import sys

root = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else "target/criterion")
rows = {}
for bench in root.glob("**/new/benchmark.json"):
    b = json.loads(bench.read_text())
    est = json.loads((bench.parent / "estimates.json").read_text())
    m = re.fullmatch(r"scene(\d)/(\d+)x(\d+)", b["group_id"])
    if not m:
        continue
    n, w, h = int(m[1]), int(m[2]), int(m[3])
    kernel, threads = b["function_id"], b["value_str"]
    rate = w * h / (est["mean"]["point_estimate"] * 1e-9) / 1e6
    rows.setdefault((n, w, h), {})[(kernel, threads)] = rate

if not rows:
    sys.exit(f"no criterion results under {root}: run `cargo bench --bench render` first")

cpu = next((l.split(":", 1)[1].strip() for l in open("/proc/cpuinfo") if l.startswith("model name")), platform.processor())
tall = max(t for r in rows.values() for (_, t) in r)
print(f"Mrays/s, mean of criterion's samples; {cpu}, {tall[1:]} cores.\n")
print("`packet`: the default renderer (BVH); `packet none`: the same packet kernel testing every")
print("primitive, like the scalar kernels. SIMD speedup = packet none / scalar f32, one thread.\n")
print(f"| scene | size | packet t1 | packet none t1 | scalar f32 t1 | scalar f64 t1 | packet {tall} | packet none {tall} | scalar f32 {tall} | SIMD speedup (t1) | packet {tall}/t1 | packet none {tall}/t1 |")
print("|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
for (n, w, h), r in sorted(rows.items()):
    g = lambda k, t: r.get((k, t), float("nan"))
    p1, q1, s1, d1 = g("packet", "t1"), g("packet_none", "t1"), g("scalar_f32", "t1"), g("scalar_f64", "t1")
    pn, qn, sn = g("packet", tall), g("packet_none", tall), g("scalar_f32", tall)
    print(f"| scene{n} | {w}x{h} | {p1:.1f} | {q1:.1f} | {s1:.2f} | {d1:.2f} | {pn:.1f} | {qn:.1f} | {sn:.2f} | {q1 / s1:.1f}x | {pn / p1:.2f}x | {qn / q1:.2f}x |")
