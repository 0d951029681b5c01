"""Scenes pickle by value, compactly, and render the same after the trip."""

import multiprocessing
import pickle

import numpy as np
import pytest

import lanecast
from conftest import MESH_SCENES, SCENES, SEED_SCENES, same_bits


def _render_in_child(scene, cam):
    out = scene.render(cam, 64, 48)
    return out.ids, out.depth


@pytest.mark.parametrize("path", SEED_SCENES + MESH_SCENES, ids=lambda p: p.name)
def test_round_trip_renders_identically(path):
    scene = lanecast.Scene.load(path)
    back = pickle.loads(pickle.dumps(scene))
    assert len(back) == len(scene) and back.counts == scene.counts
    assert back.source == scene.source and back.warnings == scene.warnings
    assert back.camera == scene.camera
    a = scene.render(width=120, height=90, zdepth=True)
    b = back.render(width=120, height=90, zdepth=True)
    assert same_bits(a.ids, b.ids) and same_bits(a.depth, b.depth)
    assert same_bits(a.zdepth, b.zdepth)
    # and from another eye, where the other primitives are in view
    cam = lanecast.Camera(eye=np.array(scene.camera.eye) * 1.3 + 0.1, look=scene.camera.look)
    a, b = scene.render(cam, 120, 90), back.render(cam, 120, 90)
    assert same_bits(a.ids, b.ids) and same_bits(a.depth, b.depth)


def test_pickles_are_compact():
    scene = lanecast.Scene.load(SCENES / "bunny.sc")
    state = scene._state()
    (_, vertices, faces, _), = [p for p in state[5] if p[0] == "mesh"]
    raw = vertices.nbytes + faces.nbytes  # float64 vertices, uint32 faces
    size = len(pickle.dumps(scene, protocol=pickle.HIGHEST_PROTOCOL))
    assert size < raw + 4096, (size, raw)
    # vs the OBJ text it came from
    assert size < (SCENES / "meshes" / "bunny.obj").stat().st_size


def test_interleaved_primitives_keep_their_ids():
    # scene2 mixes spheres, triangles and quads in file order; a mesh between loose shapes:
    text = (SCENES / "teapot.sc").read_text()
    assert "mesh" in text
    for path in (SCENES / "scene2.sc", SCENES / "teapot.sc"):
        scene = lanecast.Scene.load(path)
        state = scene._state()
        back = pickle.loads(pickle.dumps(scene))
        assert back._state()[5].__len__() == len(state[5])
        for p, q in zip(state[5], back._state()[5]):
            assert p[0] == q[0]
            for x, y in zip(p[1:], q[1:]):
                assert np.array_equal(np.asarray(x), np.asarray(y))


def test_arrays_scene_and_cameras_pickle():
    v = np.array([[-1, -1, 0], [1, -1, 0], [1, 1, 0], [-1, 1, 0]], float)
    cam = lanecast.Camera(eye=(0, 0, 4), look=(0, 0, 0), fov=45)
    scene = lanecast.Scene.from_arrays(vertices=v, triangles=[[0, 1, 2]], quads=[[0, 1, 2, 3]],
                                       spheres=[[0, 0, -1, 0.5]], camera=cam)
    back = pickle.loads(pickle.dumps(scene))
    assert same_bits(scene.render(cam, 40, 30).ids, back.render(cam, 40, 30).ids)
    assert pickle.loads(pickle.dumps(cam)) == cam
    K = np.array([[40.0, 0, 20], [0, 40, 15], [0, 0, 1]])
    ci = lanecast.Camera.from_intrinsics(K, np.eye(4), 40, 30)
    assert pickle.loads(pickle.dumps(ci)) == ci and ci.size == (40, 30)


def test_a_scene_ships_to_a_spawned_process():
    scene = lanecast.Scene.load(SCENES / "bunny.sc")
    cam = lanecast.Camera(eye=(0.2, 0.2, 0.25), look=(-0.02, 0.1, 0))
    with multiprocessing.get_context("spawn").Pool(1) as pool:
        ids, depth = pool.apply(_render_in_child, (scene, cam))
    mine = scene.render(cam, 64, 48)
    assert same_bits(ids, mine.ids) and same_bits(depth, mine.depth)


def test_a_damaged_state_is_refused():
    scene = lanecast.Scene.load(SCENES / "bunny.sc")
    state = list(scene._state())
    parts = [list(p) for p in state[5]]
    mesh = next(p for p in parts if p[0] == "mesh")
    mesh[2] = mesh[2].copy()
    mesh[2][5, 1] = 10**9
    state[5] = [tuple(p) for p in parts]
    with pytest.raises(ValueError, match="not a pickled lanecast.Scene: face index"):
        lanecast.Scene._from_state(tuple(state))
