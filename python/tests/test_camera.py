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
    (lambda K, E: K.__setitem__((0, 1), 0.5), "skew"),
    (lambda K, E: K.__setitem__((2, 2), 2.0), r"K must be"),
    (lambda K, E: K.__setitem__((1, 0), 1.0), r"K must be"),
    (lambda K, E: K.__setitem__((0, 0), -K[0, 0]), "fx = -.* positive"),
    (lambda K, E: K.__setitem__((1, 1), 0.0), "fy = 0 pixels"),
    (lambda K, E: K.__setitem__((0, 2), 1e9), "principal point cx"),
    (lambda K, E: K.__setitem__((0, 2), np.inf), "K must be finite"),
    (lambda K, E: E.__setitem__((0, 0), E[0, 0] * 1.01), "not a rigid transform"),
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


def test_within_the_rigid_tolerance_is_accepted_and_keeps_its_size():
    W, H = 64, 48
    E = np.eye(4)
    E[:3, :3] *= 1 + 0.4 * lanecast.RIGID_TOL
    cam = lanecast.Camera.from_intrinsics(intrinsics(60, W, H), E, W, H)
    with pytest.raises(ValueError, match="64x48 images"):
        lanecast.Scene.from_arrays(spheres=[[0, 0, 5, 1]], camera=cam).render(cam, 32, 24)
    E[:3, :3] *= 1 + 2 * lanecast.RIGID_TOL
    with pytest.raises(ValueError, match="not a rigid transform"):
        lanecast.Camera.from_intrinsics(intrinsics(60, W, H), E, W, H)


def reference_rays(K, E, W, H):
    """Unit directions of pixel centres (x + 0.5, y + 0.5) through K, in world axes: R^T K^-1 p."""
    u, v = np.meshgrid(np.arange(W) + 0.5, np.arange(H) + 0.5)
    p = np.stack([u, v, np.ones_like(u)], axis=-1)
    d = p @ np.linalg.inv(K).T @ E[:3, :3]
    return d / np.linalg.norm(d, axis=-1, keepdims=True)


def test_any_pinhole_matches_the_reference_formula():
    # dataset intrinsics: the principal point off the centre (OpenCV's 319.5), fx != fy, and
    # random ones far off the centre
    rng = np.random.default_rng(3)
    W, H = 640, 480
    cases = [np.array([[525.0, 0, 319.5], [0, 531.25, 239.5], [0, 0, 1]])]
    for _ in range(10):
        fx = rng.uniform(50, 2000)
        cases.append(np.array([[fx, 0, rng.uniform(-3 * W, 4 * W)],
                               [0, fx * rng.uniform(0.3, 3), rng.uniform(-3 * H, 4 * H)],
                               [0, 0, 1]]))
    for K in cases:
        E = look_at_extrinsic(rng.uniform(-9, 9, 3), rng.uniform(-1, 1, 3), (0, 1, 0))
        cam = lanecast.Camera.from_intrinsics(K, E, W, H)
        assert cam.intrinsics == (K[0, 0], K[1, 1], K[0, 2], K[1, 2])
        assert np.array_equal(cam.K(), K)
        assert np.allclose(cam.extrinsic(), E, atol=1e-12)
        mine = cam.rays()
        assert np.allclose(mine[..., :3], -E[:3, :3].T @ E[:3, 3], atol=1e-9)
        assert np.abs(mine[..., 3:] - reference_rays(K, E, W, H)).max() < 1e-12, K


def test_batches_of_intrinsics_and_their_matrices_come_back_with_the_render():
    W, H = 40, 30
    rng = np.random.default_rng(8)
    Es = np.stack([look_at_extrinsic((np.sin(a) * 4, 1, np.cos(a) * 4), (0, 0, 0), (0, 1, 0))
                   for a in np.linspace(0, 3, 4)])
    Ks = np.stack([np.array([[f, 0, W * rng.uniform(0.3, 0.7)],
                             [0, f * rng.uniform(0.8, 1.25), H * rng.uniform(0.3, 0.7)],
                             [0, 0, 1]]) for f in rng.uniform(30, 60, 4)])
    cams = lanecast.Camera.from_intrinsics(Ks, Es, W, H)
    assert len(cams) == 4
    scene = lanecast.Scene.from_arrays(spheres=[[0, 0, 0, 1]], camera=cams[0])
    out = scene.render_views(cams)
    assert out.K.shape == (4, 3, 3) and out.extrinsics.shape == (4, 4, 4)
    assert np.array_equal(out.K, Ks)
    assert np.allclose(out.extrinsics, Es, atol=1e-12)
    one = scene.render(cams[2])
    assert np.array_equal(one.K, Ks[2]) and np.array_equal(one.ids, out.ids[2])
    # a fov camera's K: fx = fy = W / (2 tan(fov / 2)), the principal point at the centre
    r = scene.render(lanecast.Camera((0, 0, 5), (0, 0, 0), fov=50), W, H)
    f = W / (2 * np.tan(np.radians(25)))
    assert np.allclose(r.K, [[f, 0, W / 2], [0, f, H / 2], [0, 0, 1]], rtol=1e-14)
    with pytest.raises(ValueError, match="K: 3 matrices for 4 extrinsics"):
        lanecast.Camera.from_intrinsics(Ks[:3], Es, W, H)


def test_rays_agree_with_open3d_create_rays_pinhole():
    o3d = pytest.importorskip("open3d")
    W, H = 80, 60
    # off the centre and not square, as calibrations give them
    K = np.array([[61.5, 0, 38.25], [0, 67.0, 31.5], [0, 0, 1]])
    E = look_at_extrinsic((1.0, 2.0, 6.0), (0.2, 0.1, 0.0), (0, 1, 0))
    theirs = o3d.t.geometry.RaycastingScene.create_rays_pinhole(
        o3d.core.Tensor(K), o3d.core.Tensor(E), W, H).numpy().astype(np.float64)
    mine = lanecast.Camera.from_intrinsics(K, E, W, H).rays()
    assert theirs.shape == mine.shape == (H, W, 6)
    assert np.allclose(theirs[..., :3], mine[..., :3], atol=1e-5)
    d = theirs[..., 3:] / np.linalg.norm(theirs[..., 3:], axis=-1, keepdims=True)
    # Open3D builds its rays in float32
    assert np.abs(d - mine[..., 3:]).max() < 1e-6
