"""lanecast for Python: cast one primary ray per pixel into a scene of triangles (meshes),
quads and spheres, and get numpy arrays of primitive ids and depths.

    import lanecast
    scene = lanecast.Scene.load("scenes/bunny.sc")          # .sc, .obj or .ply
    cams = [lanecast.Camera(eye=(0.3 * i, 0.2, 1), look=(0, 0.1, 0)) for i in range(8)]
    out = scene.render_views(cams, 640, 480)                 # out.ids, out.depth: (8, 480, 640)

Type information: the package is typed (``py.typed``; the extension's stub is
``_lanecast.pyi``). ``__version__`` is the package's version.

The engine is the lanecast Rust library (the command line's): every view is bit-identical to
``lanecast -i SCENE --eye ... --look ... --up ... -fov ...``.
"""

import copyreg as _copyreg

from ._errors import SceneError
from ._lanecast import (MAX_SIDE, MAX_THREADS, RIGID_TOL, Camera, Render, Scene,
                        __version__, shade)

__all__ = ["Camera", "Render", "Scene", "SceneError", "shade", "RIGID_TOL", "MAX_SIDE",
           "MAX_THREADS", "__version__"]


def _scene_from_state(state):
    return Scene._from_state(state)


def _camera_from_state(state):
    return Camera._from_state(state)


# Pickling by value: a scene as its camera and packed arrays (float64 vertices and shape
# numbers, uint32 faces and lines), rebuilt without re-parsing; so a Scene ships to worker
# processes (multiprocessing, Dask).
_copyreg.pickle(Scene, lambda s: (_scene_from_state, (s._state(),)))
_copyreg.pickle(Camera, lambda c: (_camera_from_state, (c._state(),)))
