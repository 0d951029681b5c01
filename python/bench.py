"""lanecast from Python against Open3D's RaycastingScene and embreex: 100 views at 1280x720.

    python python/bench.py [--views 100] [--threads 2] [--size 1280x720] [MESH.obj ...]

Default meshes: scenes/meshes/bunny.obj and target/scale/armadillo3.obj (the armadillo
midpoint-subdivided 3 times: 3,328,000 triangles; make it with
``python3 scripts/subdivide.py scenes/meshes/armadillo.obj target/scale/armadillo3.obj 3``).
A mesh that is missing is named and skipped.

Each tool reads the same OBJ file with its own reader. Per mesh:
- lanecast: end to end (Scene.load, prepare, the views into one stacked numpy array with
  render_views) and per view (scene.render, median), on ``--threads`` threads;
- Open3D (if importable): build once (read_triangle_mesh, RaycastingScene.add_triangles and
  the first cast, which builds the BVH), then per view create_rays_pinhole(K, extrinsic) and
  cast_rays(nthreads=threads); end to end the same with the views' ids and t_hit in numpy;
- embreex (if importable): the same rays, EmbreeScene.run (embreex picks its own threads).
The cameras orbit the mesh's bounding box at the framing distance of `lanecast mesh.obj`.
Ids are compared with Open3D's primitive ids on every 10th view: pixels where both hit and the
ids differ, and pixels where only one hits (rays grazing an edge or a silhouette).
"""

import argparse
import os
import platform
import statistics
import subprocess
import sys
import time

import numpy as np

import lanecast

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def cpu_model():
    try:
        out = subprocess.run(["lscpu"], capture_output=True, text=True).stdout
        for line in out.splitlines():
            if line.startswith("Model name:"):
                return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or "unknown"


def orbit(scene, n, w, h):
    """n cameras around the scene's framing camera's look point, at its distance, as
    lanecast cameras and as (K, extrinsic) in the OpenCV convention."""
    c = scene.camera
    look = np.array(c.look)
    r = np.linalg.norm(np.array(c.eye) - look)
    f = 0.5 * w / np.tan(np.radians(c.fov) / 2)
    K = np.array([[f, 0, w / 2], [0, f, h / 2], [0, 0, 1.0]])
    cams, mats = [], []
    for a in np.linspace(0, 2 * np.pi, n, endpoint=False):
        eye = look + r * np.array([np.sin(a), 0.25, np.cos(a)]) / np.linalg.norm([1, 0.25])
        z = (look - eye) / np.linalg.norm(look - eye)
        x = np.cross(z, [0, 1, 0])
        x /= np.linalg.norm(x)
        y = np.cross(z, x)
        E = np.eye(4)
        E[:3, :3] = np.stack([x, y, z])
        E[:3, 3] = -E[:3, :3] @ eye
        mats.append(E)
        cams.append(lanecast.Camera.from_intrinsics(K, E, w, h))
    return cams, K, mats


def bench_lanecast(path, n, w, h, threads):
    t0 = time.perf_counter()
    scene = lanecast.Scene.load(path)
    cams, K, mats = orbit(scene, n, w, h)
    t1 = time.perf_counter()
    out = scene.render_views(cams, w, h, threads=threads)
    t2 = time.perf_counter()
    per = []
    for c in cams:
        s = time.perf_counter()
        scene.render(c, w, h, threads=threads)
        per.append(time.perf_counter() - s)
    return scene, cams, K, mats, out, {"load_s": t1 - t0, "views_s": t2 - t1,
                                        "end_to_end_s": t2 - t0,
                                        "per_view_ms": 1e3 * statistics.median(per)}


def bench_open3d(o3d, path, K, mats, w, h, threads):
    t0 = time.perf_counter()
    mesh = o3d.t.io.read_triangle_mesh(path)
    rs = o3d.t.geometry.RaycastingScene()
    rs.add_triangles(mesh)
    Kt = o3d.core.Tensor(K)
    first = rs.cast_rays(o3d.t.geometry.RaycastingScene.create_rays_pinhole(
        Kt, o3d.core.Tensor(mats[0]), w, h), nthreads=threads)  # builds the BVH
    del first
    t1 = time.perf_counter()
    ids, per_cast, per_view = [], [], []
    for k, E in enumerate(mats):
        s = time.perf_counter()
        rays = o3d.t.geometry.RaycastingScene.create_rays_pinhole(Kt, o3d.core.Tensor(E), w, h)
        c = time.perf_counter()
        ans = rs.cast_rays(rays, nthreads=threads)
        i, t = ans["primitive_ids"].numpy(), ans["t_hit"].numpy()
        e = time.perf_counter()
        per_cast.append(e - c)
        per_view.append(e - s)
        ids.append((i, t) if k % 10 == 0 else None)
    t2 = time.perf_counter()
    return ids, {"build_s": t1 - t0, "end_to_end_s": t2 - t0,
                 "cast_ms": 1e3 * statistics.median(per_cast),
                 "per_view_ms": 1e3 * statistics.median(per_view)}


def bench_embreex(scene, cams, w, h, views):
    from embreex import rtcore_scene as rtcs
    from embreex.mesh_construction import TriangleMesh

    state = scene._state()
    (_, verts, faces, _), = [p for p in state[5] if p[0] == "mesh"]
    t0 = time.perf_counter()
    es = rtcs.EmbreeScene()
    TriangleMesh(es, verts[faces].astype(np.float32))
    t1 = time.perf_counter()
    per = []
    for c in cams[:views]:
        r = c.rays(w, h).reshape(-1, 6)
        o, d = np.ascontiguousarray(r[:, :3], np.float32), np.ascontiguousarray(r[:, 3:], np.float32)
        s = time.perf_counter()
        es.run(o, d)
        per.append(time.perf_counter() - s)
    return {"build_s": t1 - t0, "per_view_ms": 1e3 * statistics.median(per), "views": len(per)}


def agreement(mine, depth, theirs, t_hit, faces, K):
    """Pixel counts; for pixels where both hit different triangles, how many of those pairs
    share a vertex (neighbours: the ray crosses near their common edge or corner) and how many
    hit at the same distance to 1e-5 (the same point of the surface, a tie between them)."""
    theirs = theirs.astype(np.int64)
    theirs[theirs == 4294967295] = -1
    # Open3D's directions are K^-1 (x + 0.5, y + 0.5, 1) rotated: t_hit is in their lengths
    h, w = mine.shape
    u = (np.arange(w) + 0.5 - K[0, 2]) / K[0, 0]
    v = (np.arange(h) + 0.5 - K[1, 2]) / K[1, 1]
    t_hit = t_hit * np.sqrt(1 + u[None, :] ** 2 + v[:, None] ** 2)
    both = (mine >= 0) & (theirs >= 0)
    diff = both & (mine != theirs)
    a, b = mine[diff], theirs[diff]
    shared = sum(len(set(faces[x]) & set(faces[y])) > 0 for x, y in zip(a, b))
    same_t = int((np.abs(depth[diff] - t_hit[diff]) <= 1e-5 * depth[diff]).sum())
    return {"pixels": int(mine.size), "both_hit": int(both.sum()),
            "ids_differ": int(diff.sum()), "differ_neighbours": int(shared),
            "differ_same_distance": same_t,
            "only_lanecast": int(((mine >= 0) & (theirs < 0)).sum()),
            "only_open3d": int(((mine < 0) & (theirs >= 0)).sum())}


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("meshes", nargs="*")
    ap.add_argument("--views", type=int, default=100)
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--size", default="1280x720")
    ap.add_argument("--embree-views", type=int, default=20,
                    help="views timed with embreex (each is one thread's worth of work)")
    a = ap.parse_args()
    w, h = map(int, a.size.split("x"))
    meshes = a.meshes or [os.path.join(ROOT, "scenes/meshes/bunny.obj"),
                          os.path.join(ROOT, "target/scale/armadillo3.obj")]
    try:
        import open3d as o3d
    except ImportError:
        o3d = None
    try:
        import embreex  # noqa: F401
        have_embree = True
    except ImportError:
        have_embree = False
    print(f"# {' '.join([os.path.basename(sys.argv[0])] + sys.argv[1:])}")
    print(f"# CPU: {cpu_model()}, {os.cpu_count()} cores; {a.views} views at {w}x{h}, "
          f"{a.threads} threads; lanecast {lanecast.__file__}; "
          f"open3d {o3d.__version__ if o3d else 'not importable'}; "
          f"embreex {'importable' if have_embree else 'not importable'}")
    for path in meshes:
        if not os.path.exists(path):
            print(f"\n## {path}: missing, skipped")
            continue
        scene, cams, K, mats, out, lc = bench_lanecast(path, a.views, w, h, a.threads)
        print(f"\n## {os.path.relpath(path, ROOT)}: {len(scene):,} triangles")
        print(f"lanecast: load {lc['load_s']:.3f} s, {a.views} views {lc['views_s']:.3f} s, "
              f"end to end {lc['end_to_end_s']:.3f} s; per view {lc['per_view_ms']:.2f} ms "
              f"(median of {a.views} scene.render)")
        if o3d is not None:
            ids, od = bench_open3d(o3d, path, K, mats, w, h, a.threads)
            print(f"open3d:   build {od['build_s']:.3f} s, end to end {od['end_to_end_s']:.3f} s; "
                  f"per view {od['per_view_ms']:.2f} ms (rays + cast_rays), "
                  f"cast_rays alone {od['cast_ms']:.2f} ms")
            print(f"ratios:   per view {od['per_view_ms'] / lc['per_view_ms']:.1f}x "
                  f"(cast_rays alone {od['cast_ms'] / lc['per_view_ms']:.1f}x), "
                  f"end to end {od['end_to_end_s'] / lc['end_to_end_s']:.1f}x")
            (_, _, faces, _), = [p for p in scene._state()[5] if p[0] == "mesh"]
            tot = {}
            for v in range(0, a.views, 10):
                theirs, t_hit = ids[v]
                for k, x in agreement(out.ids[v], out.depth[v], theirs, t_hit, faces, K).items():
                    tot[k] = tot.get(k, 0) + x
            print(f"ids vs open3d (every 10th view): {tot}")
            del ids
        if have_embree:
            em = bench_embreex(scene, cams, w, h, a.embree_views)
            print(f"embreex:  build {em['build_s']:.3f} s; per view {em['per_view_ms']:.2f} ms "
                  f"(median of {em['views']} EmbreeScene.run) = "
                  f"{em['per_view_ms'] / lc['per_view_ms']:.1f}x lanecast's")
        del out


if __name__ == "__main__":
    main()
