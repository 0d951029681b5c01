#!/usr/bin/env python3
"""Writes the accuracy lab's stress scenes, scenes/stress/*.sc (run from the crate root).

The pixel-aligned scenes (cube, icosphere, fan, grid) use a 256x192 image, fov 90, eye at the
origin looking down -z: pixel (x, y)'s centre ray has direction (sx, sy, -1) with
sx = (2x + 1 - 256) / 256 and sy = (191 - 2y) / 256 (the camera formula of src/camera.rs with
half_w = tan(45 deg) = 1). Every vertex is placed on such a ray, V = z (sx, sy, -1), so rays
through pixel centres pass exactly (to the rounding of the decimals) through vertices, and
through shared edges wherever an edge joins lattice points with a common divisor > 1.
"""
import math
import os
import random
import sys

W, H = 256, 192


def pix(x, y, z):
    """The point at depth z (distance along -z) on the centre ray of pixel (x, y)."""
    return (z * (2 * x + 1 - W) / W, z * (H - 1 - 2 * y) / W, -z)


def snap(p):
    """p moved onto the nearest pixel-centre ray, keeping its depth."""
    z = -p[2]
    x = round((p[0] / z * W + W - 1) / 2)
    y = round((H - 1 - p[1] / z * W) / 2)
    return pix(x, y, z)


def f(v):
    return repr(float(v))


def tri(a, b, c):
    return "triangle " + "   ".join(" ".join(f(x) for x in p) for p in (a, b, c))


def quad(a, b, c, d):
    return "quad " + "   ".join(" ".join(f(x) for x in p) for p in (a, b, c, d))


def sphere(c, r):
    return "sphere " + " ".join(f(x) for x in c) + " " + f(r)


ALIGNED_CAMERA = "camera eye 0 0 0 look 0 0 -1 up 0 1 0 fov 90"


def write(name, header, lab, camera, prims):
    with open(f"scenes/stress/{name}.sc", "w") as out:
        for line in header.strip().splitlines():
            out.write("# " + line.strip() + "\n" if line.strip() else "#\n")
        out.write(f"# lab: {lab}\n" if lab else "")
        out.write("\n" + camera + "\n\n")
        out.write("\n".join(prims) + "\n")


def cube():
    front = [pix(72, 56, 10), pix(168, 56, 10), pix(168, 152, 10), pix(72, 152, 10)]
    back = [pix(112, 16, 13), pix(208, 16, 13), pix(208, 112, 13), pix(112, 112, 13)]
    faces = [
        front[::-1] if False else front,
        [back[1], back[0], back[3], back[2]],
        [front[0], back[0], back[1], front[1]],
        [front[3], front[2], back[2], back[3]],
        [front[1], back[1], back[2], front[2]],
        [front[0], front[3], back[3], back[0]],
    ]
    prims = []
    for a, b, c, d in faces:
        prims += [tri(a, b, c), tri(a, c, d)]
    write(
        "cube",
        """Closed mesh: a hexahedron ("cube" in perspective) of 12 triangles whose 8 vertices lie
        exactly on pixel-centre rays (front face at depth 10, back face at depth 13 offset by
        (+40, -40) pixels), so its front edges run along pixel rows, columns and diagonals:
        every pixel centre on them is a ray through a shared edge or vertex.
        Probes: watertightness of shared edges and vertices (holes = leaks).""",
        "size 256x192 closed 0-11",
        ALIGNED_CAMERA,
        prims,
    )


def icosphere():
    t = (1 + 5 ** 0.5) / 2
    v = [(-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0), (0, -1, t), (0, 1, t), (0, -1, -t), (0, 1, -t),
         (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1)]
    faces = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4), (11, 10, 2),
             (10, 7, 6), (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8), (3, 8, 9), (4, 9, 5),
             (2, 4, 11), (6, 2, 10), (8, 6, 7), (9, 8, 1)]
    v = [tuple(c / math.sqrt(sum(x * x for x in p)) for c in p) for p in v]
    for _ in range(2):
        cache = {}
        def mid(a, b):
            key = (min(a, b), max(a, b))
            if key not in cache:
                m = [(v[a][i] + v[b][i]) / 2 for i in range(3)]
                n = math.sqrt(sum(x * x for x in m))
                v.append(tuple(x / n for x in m))
                cache[key] = len(v) - 1
            return cache[key]
        nf = []
        for a, b, c in faces:
            ab, bc, ca = mid(a, b), mid(b, c), mid(c, a)
            nf += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]
        faces = nf
    r, cz = 5.0, 10.0
    ang = 0.3
    pts = []
    for x, y, z in v:
        x, z = x * math.cos(ang) + z * math.sin(ang), -x * math.sin(ang) + z * math.cos(ang)
        pts.append(snap((x * r, y * r, z * r - cz)))
    prims = [tri(pts[a], pts[b], pts[c]) for a, b, c in faces]
    write(
        "icosphere",
        f"""Closed mesh: an icosphere (2 subdivisions, {len(faces)} triangles, radius 5, 10 units in front
        of the eye) with every vertex moved onto the nearest pixel-centre ray (keeping its depth),
        so rays pass exactly through all {len(v)} shared vertices (and, where an edge joins lattice
        points with a common divisor, through shared edges).
        Probes: watertightness at shared vertices of a curved closed mesh (holes = leaks).""",
        f"size 256x192 closed 0-{len(faces) - 1}",
        ALIGNED_CAMERA,
        prims,
    )


def fan():
    cx, cy = 127, 95
    offs = [(48, 0), (48, 24), (48, 48), (24, 48), (0, 48), (-24, 48), (-48, 48), (-48, 24),
            (-48, 0), (-48, -24), (-48, -48), (-24, -48), (0, -48), (24, -48), (48, -48), (48, -24)]
    front, back = pix(cx, cy, 8), pix(cx, cy, 14)
    rim = [pix(cx + dx, cy + dy, 11) for dx, dy in offs]
    n = len(rim)
    prims = [tri(front, rim[i], rim[(i + 1) % n]) for i in range(n)]
    prims += [tri(back, rim[(i + 1) % n], rim[i]) for i in range(n)]
    write(
        "fan",
        """Closed mesh: two fans of 16 triangles around one vertex each (a bipyramid): apexes on the
        same pixel-centre ray (depths 8 and 14), 16 rim vertices on pixel-centre rays at depth 11,
        at lattice offsets (48, 0), (48, 24), (48, 48), ... so every spoke and rim edge runs
        through pixel centres, and the back fan's spokes lie behind the front fan's: a ray that
        leaks through a front spoke meets the back spoke, where it can leak again.
        Probes: watertightness at a vertex shared by 16 triangles and along spokes.""",
        "size 256x192 closed 0-31",
        ALIGNED_CAMERA,
        prims,
    )


def grid():
    # a tilted plane: V = z (a, b, -1) with z = 20 / (1 - 0.5 b)
    def on_plane(x, y):
        a, b = (2 * x + 1 - W) / W, (H - 1 - 2 * y) / W
        return pix(x, y, 20.0 / (1.0 - 0.5 * b))
    xs = list(range(-8, W + 9, 8))
    ys = list(range(-8, H + 9, 8))
    prims = []
    for j in range(len(ys) - 1):
        for i in range(len(xs) - 1):
            a = on_plane(xs[i], ys[j])
            b = on_plane(xs[i + 1], ys[j])
            c = on_plane(xs[i + 1], ys[j + 1])
            d = on_plane(xs[i], ys[j + 1])
            prims.append(quad(a, b, c, d))
    write(
        "grid",
        f"""A grid of {len(prims)} quads (8x8 pixels each) in a tilted plane that fills the whole view,
        vertices exactly on pixel-centre rays: one pixel column in 8 and one row in 8 lie exactly
        on shared edges, 1 pixel in 64 on a vertex shared by 4 quads, and the A-C diagonal of
        each quad (where two-triangle methods split it) runs through 8 pixel centres per quad.
        Probes: leaks through shared edges and vertices of a flat tessellation; every miss is a
        hole (the grid covers the image).""",
        f"size 256x192 closed 0-{len(prims) - 1}",
        ALIGNED_CAMERA,
        prims,
    )


def far_sphere():
    fov = math.degrees(2 * math.atan(1e-4))
    prims = [sphere((-0.4, 0.05, -1e4), 0.3), sphere((0.5, 2.5, -5e4), 1.0), sphere((4.0, -0.5, -1e5), 3.0)]
    write(
        "far_sphere",
        """Small spheres far away: radius 0.3 at 1e4, radius 1 at 5e4, radius 3 at 1e5 units, seen
        through a 0.0115 degree field of view (each about 50-60 pixels across).
        Probes: the textbook quadratic b^2 - 4ac cancels (b^2 ~ 4e8..4e10, disc ~ 4 r^2) and loses
        the spheres in f32; the stable form keeps them (error ~4u|oc| at the silhouette).""",
        "",
        f"camera eye 0 0 0 look 0 0 -1 up 0 1 0 fov {fov!r}",
        prims,
    )


def ground():
    prims = [
        sphere((0, -1e4, 0), 1e4),
        sphere((0, 0.5, -6), 0.5),
        sphere((2, 0.3, -10), 0.3),
        sphere((-3, 1, -25), 1.0),
        quad((3, 0, -14), (5, 0, -15), (5, 2, -15), (3, 2, -14)),
        tri((-20, 0, -100), (-10, 0, -100), (-15, 8, -100)),
    ]
    write(
        "ground",
        """A sphere of radius 1e4 used as the ground, seen from 1.5 units above its top (horizon
        ~173 units away, 0.5 degrees below eye level), with small spheres, a quad and a triangle
        standing on it.
        Probes: f32 where it cannot represent the scene: r^2 - |l|^2 subtracts two ~1e8 values
        (ulp 8) so the discriminant, the depth near the horizon and the horizon line itself
        carry f32 error; the naive form also cancels in -b - sqrt(disc) (t ~ 1.5 from ~2e4).""",
        "",
        "camera eye 0 1.5 0 look 0 0 -20 up 0 1 0 fov 60",
        prims,
    )


def grazing():
    fov = math.degrees(2 * math.atan(1e-4))
    y0, y1, x0, x1, zn, zf = -1e-3, 1.2e-3, -9e-4, 8e-4, -5.0, -2e4
    prims = [
        quad((x0, y0, zn), (x1, y0, zn), (x1, y0, zf), (x0, y0, zf)),  # floor
        quad((x0, y1, zf), (x1, y1, zf), (x1, y1, zn), (x0, y1, zn)),  # ceiling
        quad((x1, y0, zn), (x1, y1, zn), (x1, y1, zf), (x1, y0, zf)),  # right wall
        tri((x0, y0, zn), (x0, y0, zf), (x0, y1, zf)),  # left wall, two triangles
        tri((x0, y0, zn), (x0, y1, zf), (x0, y1, zn)),
        tri((-2e-4, -4e-4, -30.0), (3e-4, -4e-4 + 1e-5 * 2000, -2030.0), (2e-4, -5e-4, -30.0)),
    ]
    write(
        "grazing",
        """Triangles and quads nearly parallel to the rays: a corridor 1.7e-3 wide and 2.2e-3 high
        running from 5 to 2e4 units ahead, seen through a 0.0115 degree field of view, so the
        rays meet floor, ceiling and walls at 1e-7 to 1e-4 rad (1e-5 rad about 100 units
        ahead), plus a sliver triangle 2000 units long rising at 1e-5 rad.
        Probes: depth is ill-conditioned (relative error ~u / angle: ~6e-3 at 1e-5 rad in f32)
        and edges seen edge-on; corners where walls meet at grazing incidence.""",
        "",
        f"camera eye 0 0 0 look 0 0 -1 up 0 1 0 fov {fov!r}",
        prims,
    )


def tiny_far():
    rnd = random.Random(7)
    half_w = 5.5e-6
    fov = math.degrees(2 * math.atan(half_w))
    prims = []
    for j in range(40):
        for i in range(50):
            cx = (i - 24.5) * 2e-3
            cy = (j - 19.5) * 2e-3
            cz = -1e4 + rnd.uniform(-0.5, 0.5)
            phi = rnd.uniform(0, 2 * math.pi)
            pts = []
            for k in range(3):
                a = phi + k * 2 * math.pi / 3 + rnd.uniform(-0.3, 0.3)
                pts.append((cx + 6e-4 * math.cos(a), cy + 6e-4 * math.sin(a), cz + rnd.uniform(-1e-3, 1e-3)))
            prims.append(tri(*pts))
    write(
        "tiny_far",
        """2000 triangles about 1e-3 across, 1e4 units away (a 50x40 array with 2e-3 spacing and
        random depth jitter of +-0.5), seen through a 6.3e-4 degree field of view: each
        triangle subtends 1e-7 rad, about 2 f32 roundings of a ray direction.
        Probes: scenes f32 cannot represent: |V - eye| = 1e4 keeps only 1e-3 * 2^-10 of the
        triangle's shape per coordinate, and the f32 ray direction itself errs by ~6e-8 rad.""",
        "",
        f"camera eye 0 0 0 look 0 0 -1 up 0 1 0 fov {fov!r}",
        prims,
    )


def translated():
    src = open("scenes/scene1.sc").read().splitlines()
    off = 1e5
    body = []
    for line in src:
        s = line.split("#")[0].split()
        if not s:
            continue
        if s[0] == "camera":
            nums = [s[2:5], s[6:9]]
            eye = [float(x) + off for x in nums[0]]
            look = [float(x) + off for x in nums[1]]
            body_cam = "camera eye " + " ".join(f(x) for x in eye) + " look " + " ".join(f(x) for x in look) + " up 0 1 0"
        elif s[0] == "sphere":
            c = [float(x) + off for x in s[1:4]]
            body.append(sphere(c, float(s[4])))
        else:
            vals = [float(x) for x in s[1:]]
            pts = [tuple(vals[k + i] + off for i in range(3)) for k in range(0, len(vals), 3)]
            body.append((tri if len(pts) == 3 else quad)(*pts))
    write(
        "translated",
        """Scene 1 (pyramid of 4 triangles and a quad base, 5 spheres), camera included, translated
        by (1e5, 1e5, 1e5).
        Probes: storage precision. Eye-relative constants (computed in f64, then rounded) see
        exactly scene 1; constants computed in f32 from world coordinates lose ulp(1e5) =
        0.0078 per coordinate, which moves edges and breaks the pyramid's shared edges.""",
        "closed 0-4",
        body_cam,
        body,
    )


def eye_inside():
    b = [(-1, -1, -6), (1, -1, -6), (1, 1, -6), (-1, 1, -6), (-1, -1, -8), (1, -1, -8), (1, 1, -8), (-1, 1, -8)]
    b = [(x + 1.5, y + 0.3, z) for x, y, z in b]
    faces = [(0, 1, 2, 3), (5, 4, 7, 6), (4, 0, 3, 7), (1, 5, 6, 2), (3, 2, 6, 7), (4, 5, 1, 0)]
    prims = [sphere((0.5, 0.2, -0.3), 10.0)]
    for a, bb, c, d in faces:
        prims += [tri(b[a], b[bb], b[c]), tri(b[a], b[c], b[d])]
    prims += [
        sphere((-2, 1, -6), 1.0),
        tri((-4, -1, -4), (-1, -1.5, -5), (-3, 2, -7)),
        quad((-8, -2, -8), (8, -2, -8), (8, -2, 4), (-8, -2, 4)),
        sphere((0.2, -0.5, 3), 0.7),
    ]
    write(
        "eye_inside",
        """The eye inside a sphere of radius 10 that holds a closed cube (12 triangles), two
        spheres, a triangle and a floor quad running out through the sphere's wall; fov 100.
        Probes: the inside case of sphere tests (the hit is the far root: the stable form's
        t = q, the naive form's +sqrt branch), and occlusion by the enclosing sphere.""",
        "closed 1-12",
        "camera eye 0 0 0 look 0 -0.2 -1 up 0 1 0 fov 100",
        prims,
    )


def behind():
    prims = [
        sphere((0, 0, 5), 1.0),  # behind the eye
        tri((-1, -1, 3), (1, -1, 3), (0, 1, 3)),  # behind the eye
        tri((-2, -1, -3), (2, -1, -3), (0, -1, 3)),  # straddles the eye plane (floor)
        quad((1.5, -1, 4), (1.5, 1, 4), (1.5, 1, -6), (1.5, -1, -6)),  # wall straddling it
        sphere((-3, 0, 0.5), 2.0),  # straddles the eye plane, eye outside
        sphere((0, 0.3, -6), 1.0),  # in front, for reference
        tri((-0.5, 1.5, 2), (0.5, 1.5, 2), (0, 1.5, -2)),  # ceiling sliver crossing the plane
        quad((5e-4, -5e-4, -1e-3), (1.5e-3, -5e-4, -1e-3), (1.5e-3, 5e-4, -1e-3), (5e-4, 5e-4, -1e-3)),  # 1e-3 ahead
    ]
    write(
        "behind",
        """Primitives behind the eye (a sphere, a triangle), straddling the eye's plane (a floor
        triangle, a wall quad, a sphere beside the eye, a ceiling sliver), a quad 1e-3 in front
        of the eye and a reference sphere; fov 120.
        Probes: false hits (t <= 0, behind the eye) and the sign handling of each method.""",
        "",
        "camera eye 0 0 0 look 0 0 -1 up 0 1 0 fov 120",
        prims,
    )


def ties():
    def plane(x, y):
        return (x, y, -5 + 0.3 * x - 0.2 * y)
    prims = [
        tri(plane(-2, -1.5), plane(1, -1.5), plane(-0.5, 1.5)),
        tri(plane(-1, -1), plane(2, -0.5), plane(0.5, 1.8)),  # overlaps the first
        quad(plane(-1.5, -0.5), plane(0.5, -0.5), plane(0.5, 0.8), plane(-1.5, 0.8)),  # coplanar
        tri(plane(-2, -1.5), plane(1, -1.5), plane(-0.5, 1.5)),  # exact duplicate of id 0
        tri(plane(1, -1.5), plane(-0.5, 1.5), plane(-2, -1.5)),  # id 0, vertices rotated
        sphere((1.2, 1.2, -6.0), 0.8),
        sphere((1.2, 1.2, -6.0), 0.8),  # duplicate sphere
    ]
    write(
        "ties",
        """Coplanar overlapping primitives in the tilted plane z = -5 + 0.3x - 0.2y: two overlapping
        triangles, a coplanar quad, an exact duplicate of triangle 0 and a copy with its
        vertices rotated; two identical spheres.
        Probes: genuine ties (equal f64 distances, within compare::TIE_REL = 1e-5): any id among
        the tied ones is right, and the lab excuses them; exact ties go to the lower id.""",
        "",
        "camera eye 0 0 0 look 0 0 -1 up 0 1 0 fov 60",
        prims,
    )


if __name__ == "__main__":
    if not os.path.isdir("scenes/stress"):
        sys.exit("scenes/stress/ is missing here: run this script from the repository root")
    for g in (cube, icosphere, fan, grid, far_sphere, ground, grazing, tiny_far, translated, eye_inside, behind, ties):
        g()
