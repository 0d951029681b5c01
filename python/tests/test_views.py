"""render_views: one prepared scene, many cameras, stacked arrays."""

import numpy as np
import pytest

import lanecast
from conftest import SCENES, same_bits


def orbit(n, r=0.3, fov=40):
    return [lanecast.Camera(eye=(r * np.sin(a), 0.12, r * np.cos(a)), look=(-0.02, 0.1, 0), fov=fov)
            for a in np.linspace(0, 2 * np.pi, n, endpoint=False)]


@pytest.mark.parametrize("precision", ["auto", "f32", "f64"])
def test_render_views_equals_a_loop_of_render(precision):
    scene = lanecast.Scene.load(SCENES / "bunny.sc")
    cams = orbit(7)
    out = scene.render_views(cams, 96, 72, precision=precision, zdepth=True)
    assert out.ids.shape == out.depth.shape == out.zdepth.shape == (7, 72, 96)
    for v, cam in enumerate(cams):
        one = scene.render(cam, 96, 72, precision=precision, zdepth=True)
        assert same_bits(out.ids[v], one.ids), v
        assert same_bits(out.depth[v], one.depth), v
        assert same_bits(out.zdepth[v], one.zdepth), v
        assert (one.ids >= 0).sum() > 100, v
    imgs = out.image()
    assert imgs.shape == (7, 72, 96, 3)
    assert np.array_equal(imgs[3], scene.render(cams[3], 96, 72, precision=precision).image())


def test_views_agree_with_the_command_line(cli, tmp_path):
    path = SCENES / "teapot.sc"
    scene = lanecast.Scene.load(path)
    cams = [lanecast.Camera(eye=(6 * np.sin(a), 3.0, 6 * np.cos(a)), look=(0, 1, 0), fov=50)
            for a in (0.3, 2.0, 4.1)]
    out = scene.render_views(cams, 80, 60)
    for v, c in enumerate(cams):
        fmt = lambda p: ",".join(repr(float(x)) for x in p)
        ids, depth = cli(path, tmp_path, size=(80, 60),
                         args=["--eye", fmt(c.eye), "--look", fmt(c.look), "--up", fmt(c.up),
                               "-fov", "50"])
        assert same_bits(out.ids[v], ids) and same_bits(out.depth[v], depth), v


def test_cameras_of_different_sizes_are_refused():
    scene = lanecast.Scene.load(SCENES / "scene1.sc")
    K = np.array([[50.0, 0, 32], [0, 50, 24], [0, 0, 1]])
    a = lanecast.Camera.from_intrinsics(K, np.eye(4), 64, 48)
    b = lanecast.Camera.from_intrinsics(np.array([[50.0, 0, 16], [0, 50, 12], [0, 0, 1]]),
                                        np.eye(4), 32, 24)
    with pytest.raises(ValueError, match=r"cameras\[1\]"):
        scene.render_views([a, b])
    assert scene.render_views([a, a]).ids.shape == (2, 48, 64)
    assert scene.render_views([], 16, 8).ids.shape == (0, 8, 16)


def test_world_views_are_the_command_lines_world_views(cli, tmp_path):
    """accel="world": the scene prepared once and kept; each view the bytes of
    `lanecast --accel world` with its camera, alone or in any batch, in any order."""
    path = SCENES / "teapot.sc"
    scene = lanecast.Scene.load(path)
    cams = [lanecast.Camera(eye=(6 * np.sin(a), 3.0, 6 * np.cos(a)), look=(0, 1, 0), fov=50)
            for a in (0.3, 2.0, 4.1)]
    out = scene.render_views(cams, 80, 60, accel="world", zdepth=True)
    back = scene.render_views(cams[::-1], 80, 60, accel="world")
    for v, c in enumerate(cams):
        fmt = lambda p: ",".join(repr(float(x)) for x in p)
        ids, depth = cli(path, tmp_path, size=(80, 60),
                         args=["--eye", fmt(c.eye), "--look", fmt(c.look), "--up", fmt(c.up),
                               "-fov", "50", "--accel", "world"])
        assert same_bits(out.ids[v], ids) and same_bits(out.depth[v], depth), v
        assert same_bits(back.ids[2 - v], ids), v
        one = scene.render(c, 80, 60, accel="world", zdepth=True)
        assert same_bits(one.zdepth, out.zdepth[v]), v
        assert (ids >= 0).sum() > 100, v


@pytest.mark.parametrize("precision", ["auto", "f64"])
def test_world_agrees_with_the_per_eye_path(precision):
    """In f64 both engines are the oracle, bit for bit; in auto they differ only at ties."""
    scene = lanecast.Scene.load(SCENES / "bunny.sc")
    for cam in orbit(4):
        a = scene.render(cam, 96, 72, precision=precision)
        w = scene.render(cam, 96, 72, precision=precision, accel="world")
        if precision == "f64":
            assert same_bits(a.ids, w.ids) and same_bits(a.depth, w.depth)
        else:
            same = a.ids == w.ids
            assert same.mean() > 0.99
            hit = same & (a.ids >= 0)
            assert np.all(np.abs(a.depth[hit] - w.depth[hit]) <= 1e-5 * a.depth[hit])


def test_bad_accel_is_refused():
    scene = lanecast.Scene.load(SCENES / "scene1.sc")
    with pytest.raises(ValueError, match=r'accel="tiles"'):
        scene.render(accel="tiles")
    with pytest.raises(ValueError, match=r'accel="bvh"'):
        scene.render_views([scene.camera], accel="bvh")
