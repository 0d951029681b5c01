#!/usr/bin/env python3
"""Midpoint subdivision of an OBJ triangle mesh, for lanecast's scale measurements.

    python3 scripts/subdivide.py IN.obj OUT.obj LEVELS

Each level splits every triangle into four through its edge midpoints (shared edges share
their midpoint, so the mesh stays closed where it was closed; the surface does not move).
Triangle count grows 4x per level: the shared armadillo (52,000 triangles) becomes about
3.3M triangles at 3 levels (`scenes/armadillo.sc` seen with `mesh` of the result). Output
vertices are written with 6 decimals. Generated meshes are not committed: write them under
target/ (docs/performance.md: "The whole command and its phases").

Reads `v` and `f` lines only (polygons fan-triangulated, `i/t/n` and negative indices
accepted), like lanecast's own reader.
"""
import argparse
import sys


def read_obj(path):
    verts, tris = [], []
    with open(path) as f:
        for line in f:
            parts = line.split()
            if not parts:
                continue
            if parts[0] == "v":
                verts.append(tuple(float(x) for x in parts[1:4]))
            elif parts[0] == "f":
                idx = []
                for p in parts[1:]:
                    i = int(p.split("/")[0])
                    idx.append(i - 1 if i > 0 else len(verts) + i)
                for k in range(1, len(idx) - 1):
                    tris.append((idx[0], idx[k], idx[k + 1]))
    return verts, tris


def subdivide(verts, tris):
    mid = {}

    def midpoint(a, b):
        key = (a, b) if a < b else (b, a)
        m = mid.get(key)
        if m is None:
            pa, pb = verts[a], verts[b]
            verts.append(tuple((x + y) / 2 for x, y in zip(pa, pb)))
            m = mid[key] = len(verts) - 1
        return m

    out = []
    for a, b, c in tris:
        ab, bc, ca = midpoint(a, b), midpoint(b, c), midpoint(c, a)
        out += [(a, ab, ca), (ab, b, bc), (ca, bc, c), (ab, bc, ca)]
    return out


def main():
    # --help prints the usage and exits 0; a missing or bad argument exits 2 with the usage
    parser = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    parser.add_argument("src", metavar="IN.obj", help="triangle mesh to subdivide")
    parser.add_argument("dst", metavar="OUT.obj", help="where to write the result")
    parser.add_argument("levels", metavar="LEVELS", type=int, help="levels (4x triangles each)")
    args = parser.parse_args()
    if args.levels < 0:
        parser.error(f"LEVELS {args.levels}: must be 0 or more")
    src, dst, levels = args.src, args.dst, args.levels
    verts, tris = read_obj(src)
    for _ in range(levels):
        tris = subdivide(verts, tris)
    with open(dst, "w") as f:
        f.write(f"# {src} midpoint-subdivided {levels} times: {len(tris)} triangles\n")
        f.writelines(f"v {x:.6f} {y:.6f} {z:.6f}\n" for x, y, z in verts)
        f.writelines(f"f {a + 1} {b + 1} {c + 1}\n" for a, b, c in tris)
    print(f"{dst}: {len(verts)} vertices, {len(tris)} triangles", file=sys.stderr)


if __name__ == "__main__":
    main()
