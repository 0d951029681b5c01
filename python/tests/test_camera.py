"""Cameras: look-at, and from intrinsics and extrinsics in the OpenCV/Open3D convention."""

import numpy as np
import pytest

import lanecast
from conftest import SCENES, same_bits


def look_at_extrinsic(eye, look, up):
    """World-to-camera 4x4 in OpenCV axes (x right, y down, z forward)."""
    eye, look, up = map(np.asarray, (eye, look, up))
    z = (look - eye) / np.linalg.norm(look - eye)
    x = np.cross(z, up)
    x /= np.linalg.norm(x)
    y = np.cross(z, x)
    R = np.stack([x, y, z])
    E = np.eye(4)
    E[:3, :3] = R
    E[:3, 3] = -R @ eye
    return E


def intrinsics(fov_deg, w, h):
    f = 0.5 * w / np.tan(np.radians(fov_deg) / 2)
    return np.array([[f, 0, w / 2], [0, f, h / 2], [0, 0, 1]])


def test_from_intrinsics_is_the_same_camera_as_look_at():
    eye, look, up = (0.3, 0.25, 0.35), (-0.02, 0.1, 0.0), (0, 1, 0)
    cam = lanecast.Camera.from_intrinsics(intrinsics(48, 160, 100), look_at_extrinsic(eye, look, up),
                                          160, 100)
    ref = lanecast.Camera(eye, look, up, fov=48)
    assert cam.size == (160, 100)
    assert np.allclose(cam.eye, eye, atol=1e-12) and abs(cam.fov - 48) < 1e-9
    assert np.allclose(cam.rays(), ref.rays(160, 100), atol=1e-12)
    scene = lanecast.Scene.load(SCENES / "bunny.sc")
    a, b = scene.render(cam), scene.render(ref, 160, 100)
    assert a.ids.shape == (100, 160)
    # the same rays up to the last bits of f64: the same ids nearly everywhere
    assert (a.ids != b.ids).mean() < 1e-3
    assert (a.ids >= 0).sum() > 1000


def test_a_projected_point_lands_on_its_pixel():
    # OpenCV: (u, v) = K (R X + t) / z; pixel x covers u in [x, x + 1).
    W, H = 64, 48
    K = intrinsics(60, W, H)
    E = look_at_extrinsic((1.0, 2.0, 6.0), (0.2, 0.1, 0.0), (0, 1, 0))
    cam = lanecast.Camera.from_intrinsics(K, E, W, H)
    rng = np.random.default_rng(5)
    for _ in range(20):
        u, v = rng.uniform(4, W - 4), rng.uniform(4, H - 4)
        z = rng.uniform(3, 8)
        p_cam = np.linalg.inv(K) @ np.array([u, v, 1.0]) * z
        R, t = E[:3, :3], E[:3, 3]
        X = R.T @ (p_cam - t)
        # a sphere about 3 pixels in radius around it
        scene = lanecast.Scene.from_arrays(spheres=[[*X, 3 * z / K[0, 0]]], camera=cam)
        ids = scene.render(cam).ids
        assert ids[int(v), int(u)] == 0, (u, v)
        ys, xs = np.nonzero(ids == 0)
        assert abs(xs.mean() + 0.5 - u) < 0.25 and abs(ys.mean() + 0.5 - v) < 0.25, (u, v)


def test_batches_of_extrinsics_give_lists_of_cameras():
    W, H = 32, 24
    Es = np.stack([look_at_extrinsic((np.sin(a) * 4, 1, np.cos(a) * 4), (0, 0, 0), (0, 1, 0))
                   for a in np.linspace(0, 3, 5)])
    cams = lanecast.Camera.from_intrinsics(intrinsics(50, W, H), Es, W, H)
    assert isinstance(cams, list) and len(cams) == 5
    for c, E in zip(cams, Es):
        assert c == lanecast.Camera.from_intrinsics(intrinsics(50, W, H), E, W, H)
    scene = lanecast.Scene.from_arrays(spheres=[[0, 0, 0, 1]], camera=cams[0])
    out = scene.render_views(cams)
    assert out.ids.shape == (5, H, W) and (out.ids[:, H // 2, W // 2] == 0).all()
    with pytest.raises(ValueError, match="view 2"):
        bad = Es.copy()
        bad[2, :3, :3] *= 1.1
        lanecast.Camera.from_intrinsics(intrinsics(50, W, H), bad, W, H)


@pytest.mark.parametrize("change, message", [
    (lambda K, E: K.__setitem__((0, 2), K[0, 2] - 0.5), "principal point"),
    (lambda K, E: K.__setitem__((1, 2), K[1, 2] + 0.01), "principal point"),
    (lambda K, E: K.__setitem__((1, 1), K[1, 1] * 1.001), "square"),
    (lambda K, E: K.__setitem__((0, 1), 0.5), "skew"),
    (lambda K, E: K.__setitem__((2, 2), 2.0), r"K must be"),
    (lambda K, E: K.__setitem__((0, 0), -K[0, 0]), "positive"),
    (lambda K, E: E.__setitem__((0, 0), E[0, 0] * 1.01), "orthonormal"),
    (lambda K, E: E.__setitem__((slice(0, 1), slice(0, 3)), -E[0, :3]), "determinant"),
    (lambda K, E: E.__setitem__((3, 0), 1.0), "last row"),
    (lambda K, E: E.__setitem__((0, 3), np.nan), "finite"),
])
def test_intrinsics_lanecast_cannot_honour_are_refused(change, message):
    W, H = 64, 48
    K, E = intrinsics(60, W, H), look_at_extrinsic((0, 0, 5), (0, 0, 0), (0, 1, 0))
    change(K, E)
    with pytest.raises(ValueError, match=message):
        lanecast.Camera.from_intrinsics(K, E, W, H)


def test_within_the_tolerance_is_accepted():
    W, H = 64, 48
    K = intrinsics(60, W, H)
    K[0, 2] += 0.5 * lanecast.INTRINSICS_TOL * W
    K[1, 1] *= 1 + 0.5 * lanecast.INTRINSICS_TOL
    cam = lanecast.Camera.from_intrinsics(K, np.eye(4), W, H)
    with pytest.raises(ValueError, match="64x48 images"):
        lanecast.Scene.from_arrays(spheres=[[0, 0, 5, 1]], camera=cam).render(cam, 32, 24)


def test_rays_agree_with_open3d_create_rays_pinhole():
    o3d = pytest.importorskip("open3d")
    W, H = 80, 60
    K = intrinsics(55, W, H)
    E = look_at_extrinsic((1.0, 2.0, 6.0), (0.2, 0.1, 0.0), (0, 1, 0))
    theirs = o3d.t.geometry.RaycastingScene.create_rays_pinhole(
        o3d.core.Tensor(K), o3d.core.Tensor(E), W, H).numpy().astype(np.float64)
    mine = lanecast.Camera.from_intrinsics(K, E, W, H).rays()
    assert theirs.shape == mine.shape == (H, W, 6)
    assert np.allclose(theirs[..., :3], mine[..., :3], atol=1e-5)
    d = theirs[..., 3:] / np.linalg.norm(theirs[..., 3:], axis=-1, keepdims=True)
    # Open3D builds its rays in float32
    assert np.abs(d - mine[..., 3:]).max() < 1e-6
