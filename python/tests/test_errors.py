"""Scene file errors: lanecast.SceneError with the file, line and column the CLI reports."""

import pathlib
import re
import subprocess

import pytest

import lanecast
from conftest import REPO

BAD = sorted(p for p in (REPO / "tests" / "bad").glob("*.sc")
             if re.match(rb"# expect: \d+", p.read_bytes()))
# the rules that depend on the image size, which a scene file does not give (their files name
# the command line's 640x480 in their first line)
SIZED = re.compile(rb"\A# expect: [^\n]*640x480")


@pytest.mark.parametrize("path", BAD, ids=lambda p: p.name)
def test_bad_scene_raises_scene_error_like_the_command_line(cli, tmp_path, path):
    expect = int(re.match(rb"# expect: (\d+)", path.read_bytes()).group(1))
    run = subprocess.run([str(cli.exe), "-i", str(path), "-o", str(tmp_path / "x.png")],
                         capture_output=True, text=True)
    assert run.returncode == 2
    if SIZED.search(path.read_bytes()):
        # a lens refused for the image size: the scene loads (another size may take it), and a
        # render at the command line's 640x480 gives the command line's message
        scene = lanecast.Scene.load(path)
        with pytest.raises(ValueError) as e:
            scene.render()
        assert run.stderr.strip() == f"lanecast: error: {path}:{expect}:1: {e.value}"
        return
    with pytest.raises(lanecast.SceneError) as e:
        lanecast.Scene.load(path)
    err = e.value
    assert isinstance(err, ValueError)
    assert pathlib.Path(err.file) == path
    assert err.line == expect
    assert err.column is not None and err.column >= 0
    # column 0 is a message about the whole line, written FILE:LINE: as the CLI writes it
    where = f"{path}:{expect}:" + (f"{err.column}:" if err.column else "")
    assert str(err).startswith(where + " ")
    assert run.stderr.strip() == f"lanecast: error: {err}"


def test_a_missing_file_is_an_os_error(tmp_path):
    with pytest.raises(FileNotFoundError):
        lanecast.Scene.load(tmp_path / "nope.sc")


def test_a_missing_mesh_names_the_scene_line(tmp_path):
    sc = tmp_path / "s.sc"
    sc.write_text("camera eye 0 0 5 look 0 0 0 up 0 1 0\n\nmesh gone.obj\n")
    with pytest.raises(lanecast.SceneError) as e:
        lanecast.Scene.load(sc)
    assert e.value.line == 3 and "gone.obj" in str(e.value)


def test_no_camera_is_about_the_whole_file(tmp_path):
    sc = tmp_path / "s.sc"
    sc.write_text("sphere 0 0 0 1\n")
    with pytest.raises(lanecast.SceneError) as e:
        lanecast.Scene.load(sc)
    assert e.value.file == sc


def test_scene_errors_pickle():
    import pickle
    e = lanecast.SceneError("a.sc:3:4: bad", "a.sc", 3, 4)
    back = pickle.loads(pickle.dumps(e))
    assert (str(back), back.file, back.line, back.column) == ("a.sc:3:4: bad", "a.sc", 3, 4)
