"""Arguments a new user gets wrong: half an image size, negative integers, bytes paths,
missing files. Each is refused with a message naming the argument."""

import errno
import os
import pathlib

import numpy as np
import pytest

import lanecast
from conftest import SCENES

CAM = lanecast.Camera(eye=(0, 0, 5), look=(0, 0, 0))


@pytest.fixture(scope="module")
def scene():
    return lanecast.Scene.load(SCENES / "scene1.sc")


@pytest.mark.parametrize("size", [dict(width=100), dict(height=100)])
def test_one_size_without_the_other_is_refused(scene, size):
    # never a silent 100x480: both sizes, or neither (640x480)
    with pytest.raises(ValueError, match="width and height: give both"):
        scene.render(CAM, **size)
    with pytest.raises(ValueError, match="width and height: give both"):
        scene.render_views([CAM], **size)
    with pytest.raises(ValueError, match="width and height: give both"):
        CAM.rays(**size)


def test_sizes_given_together_or_not_at_all(scene):
    assert scene.render(CAM, 100, 50).ids.shape == (50, 100)
    assert scene.render(CAM, height=50, width=100).ids.shape == (50, 100)
    assert scene.render(CAM).ids.shape == (480, 640)
    # a camera from intrinsics has its size: one of the two, if given, must agree with it
    K = np.array([[50.0, 0, 40], [0, 50, 30], [0, 0, 1]])
    cam = lanecast.Camera.from_intrinsics(K, np.eye(4), 80, 60)
    assert scene.render(cam, width=80).ids.shape == (60, 80)
    with pytest.raises(ValueError, match="80x60"):
        scene.render(cam, width=100)


def _calls(scene):
    out = scene.render(CAM, 8, 6)
    K = np.array([[50.0, 0, 40], [0, 50, 30], [0, 0, 1]])
    return {
        "threads": lambda v: scene.render(CAM, 8, 6, threads=v),
        "width": lambda v: scene.render(CAM, v, 6),
        "height": lambda v: scene.render(CAM, 8, v),
        "views threads": lambda v: scene.render_views([CAM], 8, 6, threads=v),
        "views width": lambda v: scene.render_views([CAM], v, 6),
        "views height": lambda v: scene.render_views([CAM], 8, v),
        "rays width": lambda v: CAM.rays(v, 6),
        "rays height": lambda v: CAM.rays(8, v),
        "intrinsics width": lambda v: lanecast.Camera.from_intrinsics(K, np.eye(4), v, 60),
        "intrinsics height": lambda v: lanecast.Camera.from_intrinsics(K, np.eye(4), 80, v),
        "image seed": lambda v: out.image(seed=v),
        "shade seed": lambda v: lanecast.shade(out.ids, out.depth, seed=v),
    }


@pytest.mark.parametrize("call", ["threads", "width", "height", "views threads", "views width",
                                  "views height", "rays width", "rays height",
                                  "intrinsics width", "intrinsics height", "image seed",
                                  "shade seed"])
@pytest.mark.parametrize("value", [-1, -(2**70), 2**70])
def test_an_integer_out_of_range_is_a_value_error_naming_the_argument(scene, call, value):
    name = call.split()[-1]
    with pytest.raises(ValueError, match=rf"^{name}={value}: ") as e:
        _calls(scene)[call](value)
    assert not isinstance(e.value, OverflowError)


def test_zero_threads_and_sizes_name_the_argument(scene):
    for call, name in [("threads", "threads"), ("width", "width"), ("height", "height"),
                       ("rays width", "width"), ("intrinsics height", "height")]:
        with pytest.raises(ValueError, match=rf"^{name}=0: "):
            _calls(scene)[call](0)


def test_numpy_integers_are_integers(scene):
    assert scene.render(CAM, np.int64(8), np.uint16(6), threads=np.int32(1)).ids.shape == (6, 8)


def test_a_non_integer_is_a_type_error_naming_the_argument(scene):
    with pytest.raises(TypeError, match="threads"):
        scene.render(CAM, 8, 6, threads=1.5)
    with pytest.raises(TypeError, match="width"):
        scene.render(CAM, "8", 6)


def test_paths_may_be_str_bytes_or_path_like(tmp_path):
    path = SCENES / "scene1.sc"
    want = lanecast.Scene.load(path).render(width=16, height=12).ids
    for p in (str(path), os.fsencode(path), path):
        got = lanecast.Scene.load(p)
        assert np.array_equal(got.render(width=16, height=12).ids, want)

    class Custom(os.PathLike):
        def __fspath__(self):
            return os.fsencode(path)

    assert len(lanecast.Scene.load(Custom())) == len(lanecast.Scene.load(path))
    with pytest.raises(TypeError, match=r"^path: expected str, bytes or os\.PathLike, not int"):
        lanecast.Scene.load(3)


def test_a_missing_file_names_its_path_once(tmp_path):
    missing = tmp_path / "nope.sc"
    with pytest.raises(FileNotFoundError) as e:
        lanecast.Scene.load(missing)
    err = e.value
    assert err.errno == errno.ENOENT
    assert pathlib.Path(err.filename) == missing
    assert str(err).count(str(missing)) == 1, str(err)
    assert "os error" not in str(err)
    assert str(err) == f"[Errno 2] cannot read scene: No such file or directory: '{missing}'"
    with pytest.raises(FileNotFoundError) as e:
        lanecast.Scene.load(os.fsencode(missing))
    assert str(e.value).count("nope.sc") == 1
