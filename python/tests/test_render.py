"""Renders from Python against the native command line, byte for byte."""

import threading
import time

import numpy as np
import pytest

import lanecast
from conftest import MESH_SCENES, SCENES, SEED_SCENES, same_bits


@pytest.mark.parametrize("path", SEED_SCENES + MESH_SCENES, ids=lambda p: p.name)
def test_scene_renders_as_the_command_line(cli, tmp_path, path):
    scene = lanecast.Scene.load(path)
    ids, depth = cli(path, tmp_path, size=(160, 120))
    out = scene.render(width=160, height=120)
    assert same_bits(out.ids, ids)
    assert same_bits(out.depth, depth)
    assert (out.ids >= 0).any(), "the view shows the scene"
    # background is exactly where depth is +inf
    assert np.array_equal(out.ids == -1, np.isinf(out.depth))


@pytest.mark.parametrize("precision", ["f32", "f64", "auto"])
def test_precisions_are_the_command_lines(cli, tmp_path, precision):
    path = SCENES / "scene3.sc"
    ids, depth = cli(path, tmp_path, size=(96, 64), args=["--precision", precision])
    out = lanecast.Scene.load(path).render(width=96, height=64, precision=precision)
    assert same_bits(out.ids, ids) and same_bits(out.depth, depth)


def test_a_camera_of_ones_own_is_the_command_lines(cli, tmp_path):
    path = SCENES / "bunny.sc"
    scene = lanecast.Scene.load(path)
    cam = lanecast.Camera(eye=(0.25, 0.2, 0.3), look=(-0.02, 0.1, 0.0), up=(0, 1, 0.2), fov=35)
    ids, depth = cli(path, tmp_path, size=(200, 150),
                     args=["--eye", "0.25,0.2,0.3", "--look", "-0.02,0.1,0", "--up", "0,1,0.2",
                           "-fov", "35"])
    out = scene.render(cam, 200, 150)
    assert same_bits(out.ids, ids) and same_bits(out.depth, depth)
    assert (out.ids >= 0).sum() > 1000


def test_a_mesh_file_alone(cli, tmp_path):
    path = SCENES / "meshes" / "teapot.obj"
    ids, depth = cli(path, tmp_path, size=(120, 90))
    out = lanecast.Scene.load(path).render(width=120, height=90)
    assert same_bits(out.ids, ids) and same_bits(out.depth, depth)


def test_image_is_the_command_lines(cli, tmp_path):
    path = SCENES / "scene2.sc"
    _, _, img = cli(path, tmp_path, size=(64, 48), image=True, args=["-cm", "ordered"])
    out = lanecast.Scene.load(path).render(width=64, height=48)
    mine = out.image(color_mode="ordered")
    assert mine.dtype == np.uint8 and mine.shape == (48, 64, 3)
    assert np.array_equal(mine, img)
    _, _, img = cli(path, tmp_path, size=(64, 48), image=True, args=["--seed", "7", "-cv", "log"])
    assert np.array_equal(out.image(seed=7, variation="log"), img)


def test_buffers_are_handed_over_not_copied():
    out = lanecast.Scene.load(SCENES / "scene1.sc").render(width=32, height=24)
    for a in (out.ids, out.depth):
        assert a.flags.c_contiguous and a.flags.writeable
    assert out.ids.dtype == np.int32 and out.depth.dtype == np.float32
    assert out.ids.shape == (24, 32)
    # Each array owns no memory: its base is the Rust Vec it was moved from (rust-numpy's
    # container), not a copy numpy allocated.
    for a in (out.ids, out.depth):
        assert not a.flags.owndata and type(a.base).__name__ == "PySliceContainer"


def test_zdepth_of_a_wall_facing_the_camera_is_its_distance():
    # A quad 4 units in front of the eye, perpendicular to the view axis.
    v = np.array([[-50, -50, -4], [50, -50, -4], [50, 50, -4], [-50, 50, -4]], float)
    cam = lanecast.Camera(eye=(0, 0, 0), look=(0, 0, -1), up=(0, 1, 0), fov=70)
    scene = lanecast.Scene.from_arrays(vertices=v, quads=[[0, 1, 2, 3]], camera=cam)
    out = scene.render(cam, 64, 48, zdepth=True)
    assert (out.ids == 0).all()
    assert np.allclose(out.zdepth, 4.0, rtol=1e-6)
    # along the ray it is longer off-axis
    assert out.depth[0, 0] > 4.2 and abs(out.depth[24, 32] - 4.0) < 1e-3
    plain = scene.render(cam, 64, 48)
    with pytest.raises(AttributeError, match="zdepth=True"):
        plain.zdepth


def test_normals_face_the_camera_and_match_the_geometry():
    # A floor wound either way, a sphere on it: normals are +y on the floor, the sphere's
    # outward normal at the hit, unit length, zero on background; batches stack the same.
    v = np.array([[-4, 0, -4], [-4, 0, 4], [4, 0, 4], [4, 0, -4]], float)
    cam = lanecast.Camera(eye=(0, 2, 8), look=(0, 1, 0), up=(0, 1, 0), fov=60)
    scene = lanecast.Scene.from_arrays(vertices=v, triangles=[[0, 1, 2], [0, 3, 2]],
                                       spheres=[[0, 1, 0, 1]], camera=cam)
    out = scene.render(cam, 80, 60, normals=True)
    n = out.normals
    assert n.shape == (60, 80, 3) and n.dtype == np.float32
    hit = out.ids >= 0
    assert np.allclose(np.linalg.norm(n[hit], axis=-1), 1.0, atol=1e-6)
    assert (n[~hit] == 0).all()
    # from_arrays' ids: the triangles (the floor, 0 and 1), then the sphere (2)
    sphere, floor = out.ids == 2, (out.ids == 0) | (out.ids == 1)
    assert sphere.sum() > 100 and floor.sum() > 100
    assert np.allclose(n[floor], [0, 1, 0], atol=1e-7)
    # the sphere's normal: the hit point (eye + depth * ray) minus the centre
    p = np.array([0, 2, 8.0]) + out.depth[..., None] * cam.rays(80, 60)[..., 3:]
    assert np.allclose(n[sphere], (p - [0, 1, 0])[sphere], atol=1e-5)
    batch = scene.render_views([cam, cam], 80, 60, normals=True)
    assert batch.normals.shape == (2, 60, 80, 3)
    assert same_bits(batch.normals[1], n)
    with pytest.raises(AttributeError, match="normals=True"):
        scene.render(cam, 80, 60).normals


def test_threads_give_the_same_bits():
    scene = lanecast.Scene.load(SCENES / "bunny.sc")
    a = scene.render(width=160, height=120, threads=1)
    b = scene.render(width=160, height=120, threads=2)
    assert same_bits(a.ids, b.ids) and same_bits(a.depth, b.depth)
    with pytest.raises(ValueError, match="threads=0"):
        scene.render(threads=0)


def test_the_gil_is_released_while_rendering():
    scene = lanecast.Scene.load(SCENES / "bunny.sc")
    cams = [lanecast.Camera(eye=(0.3 * np.sin(a), 0.15, 0.3 * np.cos(a)), look=(-0.02, 0.1, 0))
            for a in np.linspace(0, 6, 30)]
    done = []
    t = threading.Thread(target=lambda: done.append(scene.render_views(cams, 320, 240, threads=1)))
    t.start()
    time.sleep(0.01)
    ticks = 0
    while t.is_alive():
        ticks += 1
    t.join()
    assert done and done[0].ids.shape == (30, 240, 320)
    # With the GIL held, this loop could not run during the render at all.
    assert ticks > 10_000, ticks


def test_bad_arguments_are_value_errors():
    scene = lanecast.Scene.load(SCENES / "scene1.sc")
    with pytest.raises(ValueError, match="precision"):
        scene.render(precision="f16")
    with pytest.raises(ValueError, match="^width=0: must be 1 to"):
        scene.render(width=0, height=10)
    with pytest.raises(ValueError, match="image size"):
        scene.render(width=65536, height=65536)
    with pytest.raises(ValueError, match="camera"):
        scene.render("not a camera")
    with pytest.raises(ValueError, match="same point"):
        lanecast.Camera(eye=(1, 2, 3), look=(1, 2, 3))
    with pytest.raises(ValueError, match="field of view"):
        lanecast.Camera(eye=(0, 0, 1), look=(0, 0, 0), fov=180)
    with pytest.raises(ValueError, match="color_mode"):
        scene.render(width=8, height=8).image(color_mode="pink")


def test_a_ply_file_alone(cli, tmp_path):
    # a binary little-endian PLY of the bunny's triangles, written here
    obj = (SCENES / "meshes" / "bunny.obj").read_text().splitlines()
    v = np.array([l.split()[1:4] for l in obj if l.startswith("v ")], float)
    f = np.array([[int(x.split("/")[0]) - 1 for x in l.split()[1:4]]
                  for l in obj if l.startswith("f ")], np.int32)
    ply = tmp_path / "bunny.ply"
    head = (f"ply\nformat binary_little_endian 1.0\nelement vertex {len(v)}\n"
            "property double x\nproperty double y\nproperty double z\n"
            f"element face {len(f)}\nproperty list uchar int vertex_indices\nend_header\n")
    faces = np.zeros(len(f), dtype=[("n", "u1"), ("i", "<i4", 3)])
    faces["n"], faces["i"] = 3, f
    ply.write_bytes(head.encode() + v.astype("<f8").tobytes() + faces.tobytes())
    ids, depth = cli(ply, tmp_path, size=(120, 90))
    out = lanecast.Scene.load(ply).render(width=120, height=90)
    assert same_bits(out.ids, ids) and same_bits(out.depth, depth)
    assert (out.ids >= 0).sum() > 500
