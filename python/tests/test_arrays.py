"""Scene.from_arrays: numpy geometry in, the format's rules applied, errors by array and row."""

import numpy as np
import pytest

import lanecast
from conftest import same_bits

V = np.array([[-1, -1, 0], [1, -1, 0], [1, 1, 0], [-1, 1, 0], [0, 0, 0]], dtype=float)
CAM = lanecast.Camera(eye=(0.5, 0.8, 5), look=(0, 0, 0), up=(0, 1, 0), fov=50)


def test_arrays_render_as_the_same_scene_written_as_text(cli, tmp_path):
    # triangles, then quads, then spheres: the ids of the equivalent .sc file's lines
    rng = np.random.default_rng(3)
    verts = rng.uniform(-2, 2, size=(30, 3))
    tris = rng.integers(0, 30, size=(20, 3))
    tris = tris[[len(set(t)) == 3 for t in tris]]
    quads = np.array([[0, 1, 2, 3]])
    qv = np.array([[-3, -2.5, -3], [3, -2.5, -3], [3, -2.5, 3], [-3, -2.5, 3]], float)
    verts = np.vstack([qv, verts])
    tris = tris + 4
    spheres = np.array([[0.5, 0.5, 0.5, 0.7], [-1.5, 1, -1, 0.4]])
    cam = lanecast.Camera(eye=(1, 2, 7), look=(0, 0, 0), up=(0, 1, 0), fov=55)
    scene = lanecast.Scene.from_arrays(vertices=verts, triangles=tris, quads=quads,
                                       spheres=spheres, camera=cam)
    assert len(scene) == len(tris) + 1 + 2
    assert scene.counts == (2, len(tris), 1)
    f = lambda xs: " ".join(repr(float(x)) for x in np.ravel(xs))
    lines = ["camera eye 1 2 7 look 0 0 0 up 0 1 0 fov 55"]
    lines += [f"triangle {f(verts[t])}" for t in tris]
    lines += [f"quad {f(verts[q])}" for q in quads]
    lines += [f"sphere {f(s)}" for s in spheres]
    sc = tmp_path / "same.sc"
    sc.write_text("\n".join(lines) + "\n")
    ids, depth = cli(sc, tmp_path, size=(120, 90))
    out = scene.render(cam, 120, 90)
    assert same_bits(out.ids, ids) and same_bits(out.depth, depth)
    assert len(np.unique(out.ids)) > 5


def test_without_a_camera_the_triangles_are_framed_like_a_mesh_file(cli, tmp_path):
    obj = tmp_path / "m.obj"
    obj.write_text("".join(f"v {x} {y} {z}\n" for x, y, z in V) + "f 1 2 3\nf 1 3 4\n")
    ids, depth = cli(obj, tmp_path, size=(50, 40))
    scene = lanecast.Scene.from_arrays(vertices=V, triangles=[[0, 1, 2], [0, 2, 3]])
    out = scene.render(width=50, height=40)
    assert same_bits(out.ids, ids) and same_bits(out.depth, depth)


def test_any_integer_dtype_and_lists_are_accepted():
    for dt in (np.int8, np.uint16, np.int32, np.uint64, np.int64):
        s = lanecast.Scene.from_arrays(vertices=V, triangles=np.array([[0, 1, 2]], dt), camera=CAM)
        assert len(s) == 1
    s = lanecast.Scene.from_arrays(vertices=V.tolist(), quads=[[0, 1, 2, 3]], camera=CAM)
    assert len(s) == 1
    # Fortran order and float32 vertices are converted
    s = lanecast.Scene.from_arrays(vertices=np.asfortranarray(V.astype(np.float32)),
                                   triangles=[[0, 1, 2]], camera=CAM)
    assert (s.render(CAM, 32, 32).ids == 0).any()


@pytest.mark.parametrize("kwargs, message", [
    (dict(vertices=V[:, :2], triangles=[[0, 1, 2]]), r"^vertices: shape \(5, 2\), expected \(N, 3\)"),
    (dict(vertices=V, triangles=[0, 1, 2]), r"^triangles: shape \(3,\), expected \(N, 3\)"),
    (dict(vertices=V, quads=[[0, 1, 2]]), r"^quads: shape \(1, 3\), expected \(N, 4\)"),
    (dict(vertices=V, triangles=np.array([[0, 1, 2.0]])), r"^triangles: dtype float64, expected integer"),
    (dict(vertices=V.astype(object), triangles=[[0, 1, 2]]), r"^vertices: dtype object"),
    (dict(vertices=np.array(["a", "b", "c"]).reshape(1, 3)), r"^vertices: dtype <U1"),
    (dict(vertices=[[0, 1], [2]]), r"^vertices: not an array of numbers"),
    (dict(vertices=np.where(np.arange(15).reshape(5, 3) == 7, np.nan, V)), r"^vertices row 2: .* is not finite"),
    (dict(vertices=np.where(np.arange(15).reshape(5, 3) == 14, np.inf, V)), r"^vertices row 4: "),
    (dict(vertices=V, triangles=[[0, 1, 2], [3, 4, 5]]), r"^triangles row 1: index 5 is out of range for 5 vertices"),
    (dict(vertices=V, triangles=[[0, -1, 2]]), r"^triangles row 0: index -1 is out of range"),
    (dict(vertices=V, triangles=np.array([[0, 2**64 - 1, 1]], np.uint64)), r"^triangles row 0: index .* is out of range"),
    (dict(vertices=V, quads=[[0, 1, 2, 3], [0, 2, 1, 3]]), r"^quads row 1: quad is not convex"),
    (dict(vertices=V, quads=[[0, 1, 4, 2]]), r"^quads row 0: degenerate quad"),
    (dict(vertices=V, spheres=[[0, 0, 0, 1], [0, 0, 0, 0]]), r"^spheres row 1: sphere radius must be positive"),
    (dict(vertices=V, spheres=[[0, np.nan, 0, 1]]), r"^spheres row 0: .* is not finite"),
    (dict(vertices=V, camera=None), r"^camera: none given, and the primitives have no extent"),
    (dict(vertices=V, triangles=[[4, 4, 4]], camera=None), r"^camera: none given"),
    (dict(vertices=np.vstack([V, [[0, 0, -1e19]]]), spheres=[[0, 0, -1e19, 1]]), r"^spheres row 0: sphere reaches"),
])
def test_bad_arrays_raise_value_error_naming_array_and_row(kwargs, message):
    kwargs.setdefault("camera", CAM)
    with pytest.raises(ValueError, match=message) as e:
        lanecast.Scene.from_arrays(**kwargs)
    assert not isinstance(e.value, lanecast.SceneError)


def test_zero_area_triangles_are_kept_with_a_warning():
    s = lanecast.Scene.from_arrays(vertices=V, triangles=[[0, 4, 2], [0, 1, 2]], camera=CAM)
    assert len(s) == 2
    assert s.warnings == ["<arrays>: 1 degenerate triangle kept (never hit)"]
    ids = s.render(CAM, 64, 64).ids
    assert (ids == 1).any() and not (ids == 0).any()


def test_a_scene_of_nothing_but_a_camera_renders_background():
    s = lanecast.Scene.from_arrays(camera=CAM)
    out = s.render(CAM, 8, 8)
    assert (out.ids == -1).all() and np.isinf(out.depth).all()


@pytest.mark.parametrize("kwargs, message", [
    (dict(spheres=[[0, 0, 0, 0]]), r"^spheres row 0: sphere radius must be positive"),
    (dict(spheres=[[0, 0, 0, -1]]), r"^spheres row 0: sphere radius must be positive"),
    (dict(spheres=[[0, 0, 0, np.nan]]), r"^spheres row 0: .* is not finite"),
    (dict(vertices=np.where(np.arange(15).reshape(5, 3) == 8, 0.5, V), quads=[[0, 1, 2, 3]]),
     r"^quads row 0: quad is not planar"),
    (dict(quads=[[0, 2, 1, 3]]), r"^quads row 0: quad is not convex"),
    (dict(triangles=[[0, 1, 2]], spheres=[[0, 0, 0, 1], [0, 0, 0, -2]]),
     r"^spheres row 1: sphere radius must be positive"),
])
def test_without_a_camera_a_bad_row_reports_its_own_error(kwargs, message):
    # validation first, then framing: never "camera: none given" in place of the real error
    kwargs.setdefault("vertices", V)
    with pytest.raises(ValueError, match=message):
        lanecast.Scene.from_arrays(**kwargs)


def test_without_a_camera_spheres_and_quads_are_framed_too():
    # a sphere alone: framed as the box around it, looking at its centre
    s = lanecast.Scene.from_arrays(spheres=[[3, 2, 1, 0.5]])
    assert s.camera.look == [3, 2, 1]
    out = s.render(width=64, height=48)
    assert (out.ids == 0).sum() > 100 and out.ids[24, 32] == 0
    # a quad alone
    q = lanecast.Scene.from_arrays(vertices=V + [10, 0, 0], quads=[[0, 1, 2, 3]])
    assert q.camera.look == [10, 0, 0]
    # a triangle and a sphere far from it: both in view, the camera at their middle
    both = lanecast.Scene.from_arrays(vertices=V, triangles=[[0, 1, 2]],
                                      spheres=[[10, 0, 0, 1]])
    assert both.camera.look == [5, 0, 0]
    ids = both.render(width=160, height=120).ids
    assert (ids == 0).any() and (ids == 1).any()
    # whole: nothing touches the image's border
    border = np.concatenate([ids[0], ids[-1], ids[:, 0], ids[:, -1]])
    assert (border == -1).all()
