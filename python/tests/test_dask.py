"""lanecast.dask on a real LocalCluster of two worker processes, on loopback."""

import os
import signal
import threading
import time

import numpy as np
import pytest

import lanecast
from conftest import SCENES, same_bits

distributed = pytest.importorskip("distributed")
import lanecast.dask as ldask  # noqa: E402


@pytest.fixture(scope="module")
def client():
    cluster = distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                       host="127.0.0.1", dashboard_address=None,
                                       silence_logs=40)
    c = distributed.Client(cluster)
    yield c
    c.close()
    cluster.close()


def orbit(n, r=0.3):
    return [lanecast.Camera(eye=(r * np.sin(a), 0.12, r * np.cos(a)), look=(-0.02, 0.1, 0), fov=40)
            for a in np.linspace(0, 2 * np.pi, n, endpoint=False)]


def load_all(out_dir, n, outputs):
    return {o: np.stack([np.load(os.path.join(out_dir, ldask.view_name(v, n), f"{o}.npy"))
                         for v in range(n)]) for o in outputs}


def listing(out_dir):
    return sorted(os.listdir(out_dir))


def test_outputs_equal_the_single_process_render_views(client, tmp_path):
    scene = lanecast.Scene.load(SCENES / "bunny.sc")
    cams = orbit(24)
    outputs = ("ids", "depth", "zdepth", "image")
    s = ldask.render_views(client, scene, cams, tmp_path, 64, 48, outputs=outputs, chunk_size=5)
    assert s.done == list(range(24)) and s.skipped == [] and s.failed == {} and s.complete
    got = load_all(tmp_path, 24, outputs)
    ref = scene.render_views(cams, 64, 48, zdepth=True)
    assert same_bits(got["ids"], ref.ids) and same_bits(got["depth"], ref.depth)
    assert same_bits(got["zdepth"], ref.zdepth)
    assert np.array_equal(got["image"], np.stack([scene.render(c, 64, 48).image() for c in cams]))
    # both workers took part, and each kept one scene across its tasks
    cached = client.run(lambda: len(__import__("lanecast.dask").dask._SCENES))
    assert len(cached) == 2 and all(n == 1 for n in cached.values())
    # a rerun renders nothing
    again = ldask.render_views(client, scene, cams, tmp_path, 64, 48, outputs=outputs)
    assert again.done == [] and again.skipped == list(range(24)) and again.failed == {}
    assert listing(tmp_path) == [ldask.view_name(v, 24) for v in range(24)]


def test_a_scene_path_is_loaded_by_each_worker(client, tmp_path):
    cams = orbit(6)
    s = ldask.render_views(client, str(SCENES / "bunny.sc"), cams, tmp_path, 40, 30)
    assert s.done == list(range(6))
    ref = lanecast.Scene.load(SCENES / "bunny.sc").render_views(cams, 40, 30)
    got = load_all(tmp_path, 6, ("ids", "depth"))
    assert same_bits(got["ids"], ref.ids) and same_bits(got["depth"], ref.depth)


def test_failures_are_reported_per_view_and_rendered_by_the_next_run(client, tmp_path):
    scene = lanecast.Scene.load(SCENES / "scene1.sc")
    far = lanecast.Camera(eye=(0, 0, 3e18), look=(0, 0, 0))  # the f32 range rule refuses it
    cams = [scene.camera, far, scene.camera]
    s = ldask.render_views(client, scene, cams, tmp_path, 32, 24)
    assert s.done == [0, 2] and list(s.failed) == [1]
    assert "from the camera eye" in s.failed[1]
    assert not os.path.exists(os.path.join(tmp_path, ldask.view_name(1, 3)))
    cams[1] = lanecast.Camera(eye=(0, 1, 9), look=(0, 0, 0))
    s = ldask.render_views(client, scene, cams, tmp_path, 32, 24)
    assert s.done == [1] and s.skipped == [0, 2] and s.complete


def test_a_worker_killed_mid_run_then_a_rerun_gives_the_complete_set(client, tmp_path):
    scene = lanecast.Scene.load(SCENES / "bunny.sc")
    n = 240
    cams = orbit(n)
    outputs = ("ids", "depth")
    pids = client.run(os.getpid)
    result = {}
    run = threading.Thread(target=lambda: result.update(
        s=ldask.render_views(client, scene, cams, tmp_path, 320, 240, outputs=outputs,
                             chunk_size=4)))
    run.start()
    # kill one worker once some views are on disk, well before the end
    deadline = time.time() + 120
    while time.time() < deadline:
        finished = [e for e in os.listdir(tmp_path) if e.startswith("view_")]
        if len(finished) >= 12:
            break
        time.sleep(0.005)
    victim = sorted(pids.values())[0]
    os.kill(victim, signal.SIGKILL)
    at_kill = len([e for e in os.listdir(tmp_path) if e.startswith("view_")])
    run.join(timeout=300)
    assert not run.is_alive()
    assert 12 <= at_kill < n, at_kill
    first = result["s"]
    print(f"killed worker {victim} with {at_kill} of {n} views on disk; first run: {first}")
    # every view is accounted for once: done, found complete (written by the killed worker
    # before it died, its task then re-run by Dask elsewhere) or failed
    assert sorted(first.done + first.skipped + list(first.failed)) == list(range(n))
    for e in os.listdir(tmp_path):
        if e.startswith("view_"):
            assert sorted(os.listdir(os.path.join(tmp_path, e))) == ["depth.npy", "ids.npy"]

    client.wait_for_workers(2, timeout=60)
    second = ldask.render_views(client, scene, cams, tmp_path, 320, 240, outputs=outputs)
    assert second.failed == {}
    assert sorted(second.done + second.skipped) == list(range(n))
    assert second.skipped == sorted(first.done + first.skipped)
    # nothing duplicated or torn: exactly one folder per view, no temporaries, every file whole
    assert listing(tmp_path) == [ldask.view_name(v, n) for v in range(n)]
    got = load_all(tmp_path, n, outputs)
    ref = scene.render_views(cams, 320, 240)
    assert same_bits(got["ids"], ref.ids) and same_bits(got["depth"], ref.depth)


JOB = """
import sys, numpy as np, distributed, lanecast, lanecast.dask
sys.path.insert(0, {tests!r})
from test_dask import orbit
client = distributed.Client({address!r})
scene = lanecast.Scene.load({scene!r})
print(lanecast.dask.render_views(client, scene, orbit({n}), {out!r}, 320, 240, chunk_size=2))
"""


def test_a_job_killed_mid_run_then_a_rerun_gives_the_complete_set(client, tmp_path):
    import subprocess
    import sys
    n, scene_path = 200, str(SCENES / "bunny.sc")
    code = JOB.format(tests=os.path.dirname(__file__), address=client.scheduler.address,
                      scene=scene_path, n=n, out=str(tmp_path))
    job = subprocess.Popen([sys.executable, "-c", code], stdout=subprocess.PIPE,
                           stderr=subprocess.PIPE)
    deadline = time.time() + 120
    while time.time() < deadline and job.poll() is None:
        if len([e for e in os.listdir(tmp_path) if e.startswith("view_")]) >= 8:
            break
        time.sleep(0.005)
    job.kill()
    job.wait()
    at_kill = len([e for e in os.listdir(tmp_path) if e.startswith("view_")])
    assert 8 <= at_kill < n, (at_kill, job.stderr.read()[-2000:])
    scene = lanecast.Scene.load(scene_path)
    cams = orbit(n)
    again = ldask.render_views(client, scene, cams, tmp_path, 320, 240)
    print(f"job killed with {at_kill} of {n} views on disk; rerun: {again}")
    assert again.failed == {} and sorted(again.done + again.skipped) == list(range(n))
    assert len(again.skipped) >= at_kill
    assert listing(tmp_path) == [ldask.view_name(v, n) for v in range(n)]
    got = load_all(tmp_path, n, ("ids", "depth"))
    ref = scene.render_views(cams, 320, 240)
    assert same_bits(got["ids"], ref.ids) and same_bits(got["depth"], ref.depth)


@pytest.mark.parametrize("kwargs, message", [
    (dict(width=100), r"^width and height: give both"),
    (dict(height=100), r"^width and height: give both"),
    (dict(width=-1, height=10), r"^width=-1: must be 1 to"),
    (dict(width=10, height=2**70), r"^height=1180591620717411303424: must be 1 to"),
    (dict(threads=-1), r"^threads=-1: must be 1 to"),
    (dict(chunk_size=0), r"^chunk_size=0: must be 1 to"),
    (dict(chunk_size=-1), r"^chunk_size=-1: must be 1 to"),
])
def test_bad_arguments_are_refused_before_any_task(client, tmp_path, kwargs, message):
    scene = lanecast.Scene.load(SCENES / "scene1.sc")
    with pytest.raises(ValueError, match=message):
        ldask.render_views(client, scene, orbit(2), tmp_path / "out", **kwargs)
    assert not (tmp_path / "out").exists()


def test_bytes_paths_are_paths(client, tmp_path):
    out = os.fsencode(tmp_path / "out")
    s = ldask.render_views(client, os.fsencode(SCENES / "scene1.sc"), orbit(2), out, 16, 12)
    assert s.complete and s.done == [0, 1]
