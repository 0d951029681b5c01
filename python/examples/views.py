# python/examples/views.py: a dataset of views, each bit-identical to lanecast -i's
import numpy as np

import lanecast

scene = lanecast.Scene.load("scenes/bunny.sc")          # .sc, .obj, .ply; or Scene.from_arrays(...)
cams = [lanecast.Camera((20 * np.cos(a), 9, 20 * np.sin(a)), (0, 4.7, 0), fov=42)
        for a in np.linspace(0, 2 * np.pi, 24, endpoint=False)]  # or Camera.from_intrinsics(K, (V,4,4), w, h)
out = scene.render_views(cams, 640, 360, threads=2)     # one prepared scene, GIL released
print(out.ids.shape, out.ids.dtype, out.depth.dtype)    # (24, 360, 640) int32 (-1: none) float32
np.savez_compressed("views.npz", ids=out.ids, depth=out.depth)  # about 7 MB
