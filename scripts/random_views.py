#!/usr/bin/env python3
"""A views file of random poses around a scene's look point, for lanecast's --views.

    python3 scripts/random_views.py SCENE.sc N [SEED] > views.txt

Reads the scene's `camera eye X Y Z look X Y Z ...` line; writes up to N `camera` lines whose
eyes lie in uniformly random directions from the look point (those within 18 degrees of the
up axis, +-y, are dropped), at 0.6 to 1.2 times the scene camera's distance, each looking at
the look point, up +y, fov 40. Python's `random` with SEED (default 7), so a run repeats.
A dataset of unrelated poses, where one view tells little about the next (docs/performance.md,
"Many views").
"""
import math
import random
import sys


def main():
    if len(sys.argv) not in (3, 4):
        sys.exit(__doc__)
    scene, n = sys.argv[1], int(sys.argv[2])
    random.seed(int(sys.argv[3]) if len(sys.argv) == 4 else 7)
    with open(scene) as f:
        words = next(line.split() for line in f if line.startswith("camera"))
    eye = [float(x) for x in words[words.index("eye") + 1:][:3]]
    look = [float(x) for x in words[words.index("look") + 1:][:3]]
    dist = math.dist(eye, look)
    for _ in range(n):
        d = [random.gauss(0, 1) for _ in range(3)]
        norm = math.sqrt(sum(x * x for x in d))
        d = [x / norm for x in d]
        r = dist * random.uniform(0.6, 1.2)
        e = [look[i] + d[i] * r for i in range(3)]
        if abs(d[1]) > 0.95:
            continue
        print("camera eye %.4f %.4f %.4f look %g %g %g up 0 1 0 fov 40" % (*e, *look))


if __name__ == "__main__":
    main()
