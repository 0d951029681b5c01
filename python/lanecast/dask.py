"""Batches of views on a Dask cluster (``pip install ./python[dask]``).

    from distributed import Client, LocalCluster
    import lanecast, lanecast.dask

    if __name__ == "__main__":  # the workers import a script: its work goes under this guard
        scene = lanecast.Scene.load("scenes/bunny.sc")
        with LocalCluster(n_workers=2, threads_per_worker=1) as cluster, Client(cluster) as client:
            summary = lanecast.dask.render_views(client, scene, cameras, "out", 1280, 720)

A complete script: python/examples/dask_views.py (README "Python").

How it works:

- The views are split into tasks of ``chunk_size`` consecutive views. The scene is scattered
  to every worker once (pickled by value: packed arrays, not the scene file), or, given as a
  path, loaded by each worker once. Each worker keeps it in a process-wide cache keyed by the
  scene's digest, with its prepared views, for every task it runs.
- Each view is written to ``OUT/view_NNNNNN/`` (its index, zero-padded), one ``.npy`` file per
  output (``ids.npy`` int32, ``depth.npy`` float32, ``zdepth.npy`` float32, ``image.npy``
  uint8 HxWx3). All or nothing: the files are written and fsynced in a temporary folder
  beside it (``.view_NNNNNN.PID.RANDOM.lanecast-tmp``), which is then renamed into place in
  one step. A view folder that exists is complete.
- A rerun skips the views already complete, so a lost worker or a killed job costs only its
  unfinished views. Dask itself re-runs the tasks of a worker that dies mid-run on another
  worker; views that still fail are reported, and the next run renders them.
- The folder must be one every worker and the client can see (a shared file system when the
  workers are on several machines). One run writes into a folder at a time: a run starts by
  removing the temporary folders that killed workers left there.

Workers should run one Dask thread each (``--nthreads 1``): each task renders on ``threads``
threads (None: all the worker machine's cores).
"""

from __future__ import annotations

import dataclasses
import errno
import hashlib
import math
import operator
import os
import pickle
import shutil
import uuid

import numpy as np

import lanecast

OUTPUTS = ("ids", "depth", "zdepth", "image")
_TMP_SUFFIX = ".lanecast-tmp"

# On a worker: scene digest -> Scene (whose prepared views it keeps), for every task.
_SCENES: dict = {}


@dataclasses.dataclass
class Summary:
    """What a run did: view indices rendered and written now (``done``), already complete
    (``skipped``), and those that failed with the reason (``failed``: index -> message)."""

    done: list
    skipped: list
    failed: dict

    @property
    def complete(self) -> bool:
        """True when every view is on disk (none failed)."""
        return not self.failed

    def __str__(self):
        return (f"{len(self.done)} views done, {len(self.skipped)} skipped (already complete), "
                f"{len(self.failed)} failed")


def view_name(index: int, count: int) -> str:
    """The folder name of view ``index`` of ``count``: ``view_`` and the index, zero-padded
    to six digits or as many as the largest index needs."""
    digits = max(6, len(str(max(count - 1, 0))))
    return f"view_{index:0{digits}d}"


def _complete(path: str, outputs) -> bool:
    return all(os.path.isfile(os.path.join(path, f"{o}.npy")) for o in outputs)


def _fsync_dir(path: str):
    fd = os.open(path, os.O_RDONLY)
    try:
        os.fsync(fd)
    finally:
        os.close(fd)


def _write_view(out_dir: str, name: str, arrays: dict) -> bool:
    """Writes one view's arrays all or nothing; False when another task had just written the
    same view (Dask may run a task twice), whose files are kept."""
    final = os.path.join(out_dir, name)
    tmp = os.path.join(out_dir, f".{name}.{os.getpid()}.{uuid.uuid4().hex[:12]}{_TMP_SUFFIX}")
    os.mkdir(tmp)
    try:
        for key, a in arrays.items():
            with open(os.path.join(tmp, f"{key}.npy"), "wb") as f:
                np.save(f, a)
                f.flush()
                os.fsync(f.fileno())
        _fsync_dir(tmp)
        try:
            os.rename(tmp, final)
        except OSError as e:
            if e.errno not in (errno.EEXIST, errno.ENOTEMPTY):
                raise
            if _complete(final, arrays):
                return False
            # an older, smaller set of outputs: replace it whole
            old = f"{tmp}.old"
            os.rename(final, old)
            os.rename(tmp, final)
            shutil.rmtree(old, ignore_errors=True)
        _fsync_dir(out_dir)
        return True
    finally:
        if os.path.exists(tmp):
            shutil.rmtree(tmp, ignore_errors=True)


def _scene_on_worker(payload, digest: str):
    scene = _SCENES.get(digest)
    if scene is None:
        kind, value = payload
        scene = lanecast.Scene.load(value) if kind == "path" else value
        _SCENES[digest] = scene
    return scene


def _render_chunk(payload, digest, views, out_dir, width, height, outputs, precision, threads,
                  count):
    """One task: render views [(index, camera)] not already complete and write each."""
    scene = _scene_on_worker(payload, digest)
    done, skipped, failed = [], [], {}
    for index, camera in views:
        name = view_name(index, count)
        if _complete(os.path.join(out_dir, name), outputs):
            skipped.append(index)
            continue
        try:
            out = scene.render(camera, width, height, precision=precision, threads=threads,
                               zdepth="zdepth" in outputs)
            arrays = {}
            for o in outputs:
                arrays[o] = out.image() if o == "image" else getattr(out, o)
            (done if _write_view(out_dir, name, arrays) else skipped).append(index)
        except Exception as e:  # reported per view; the others go on
            failed[index] = f"{type(e).__name__}: {e}"
    return done, skipped, failed


def _int_arg(name: str, value, lo: int, hi: int):
    """An integer argument (None passes) in ``lo..=hi``, as the extension checks its own: a
    ValueError naming it when out of range, a TypeError when not an integer."""
    if value is None:
        return None
    try:
        v = operator.index(value)
    except TypeError:
        raise TypeError(f"{name}: expected an integer, not {type(value).__name__}") from None
    if not lo <= v <= hi:
        raise ValueError(f"{name}={v}: must be {lo} to {hi}")
    return v


def _remove_stale_temporaries(out_dir: str):
    for entry in os.listdir(out_dir):
        if entry.endswith(_TMP_SUFFIX) or entry.endswith(_TMP_SUFFIX + ".old"):
            shutil.rmtree(os.path.join(out_dir, entry), ignore_errors=True)


def render_views(client, scene, cameras, out_dir, width=None, height=None,
                 outputs=("ids", "depth"), precision="auto", threads=None, chunk_size=None):
    """Renders ``cameras`` of ``scene`` on the Dask ``client``'s workers into ``out_dir``
    (see the module's documentation) and returns a :class:`Summary`.

    ``scene``: a :class:`lanecast.Scene` (shipped by value) or a path every worker can read.
    ``cameras``: a sequence of :class:`lanecast.Camera`. ``outputs``: any of "ids", "depth",
    "zdepth", "image". ``width`` and ``height``: both, or neither (each camera's own size,
    else 640x480), as for ``Scene.render``. ``chunk_size``: views per task (default: about
    four tasks per worker thread, at most 64 views each). Bad arguments raise here, before any
    task is sent.
    """
    import distributed

    width = _int_arg("width", width, 1, lanecast.MAX_SIDE)
    height = _int_arg("height", height, 1, lanecast.MAX_SIDE)
    threads = _int_arg("threads", threads, 1, lanecast.MAX_THREADS)
    chunk_size = _int_arg("chunk_size", chunk_size, 1, 2**63 - 1)
    outputs = tuple(outputs)
    bad = [o for o in outputs if o not in OUTPUTS]
    if bad or not outputs:
        raise ValueError(f"outputs={outputs!r}: each must be one of {OUTPUTS}")
    cameras = list(cameras)
    for v, c in enumerate(cameras):
        if not isinstance(c, lanecast.Camera):
            raise ValueError(f"cameras[{v}]: expected a lanecast.Camera")
    if (width is None) != (height is None) and any(c.size is None for c in cameras):
        given = f"width={width}" if height is None else f"height={height}"
        raise ValueError(f"width and height: give both, or neither for 640x480 (got {given} "
                         "alone; the camera's field of view is horizontal, so no height "
                         "follows from a width)")
    out_dir = os.path.abspath(os.fsdecode(out_dir))
    os.makedirs(out_dir, exist_ok=True)
    _remove_stale_temporaries(out_dir)

    if isinstance(scene, lanecast.Scene):
        digest = hashlib.sha256(pickle.dumps(scene, protocol=pickle.HIGHEST_PROTOCOL)).hexdigest()
        payload = ("scene", client.scatter(scene, broadcast=True, hash=False))
    else:
        path = os.path.abspath(os.fsdecode(scene))
        st = os.stat(path)
        digest = hashlib.sha256(f"{path}\0{st.st_size}\0{st.st_mtime_ns}".encode()).hexdigest()
        payload = ("path", path)

    count = len(cameras)
    skipped = [v for v in range(count)
               if _complete(os.path.join(out_dir, view_name(v, count)), outputs)]
    have = set(skipped)
    pending = [v for v in range(count) if v not in have]
    if chunk_size is None:
        slots = max(1, sum(client.nthreads().values()))
        chunk_size = min(64, max(1, math.ceil(len(pending) / (4 * slots))))
    chunks = [pending[i:i + chunk_size] for i in range(0, len(pending), chunk_size)]
    futures = {}
    for chunk in chunks:
        views = [(v, cameras[v]) for v in chunk]
        f = client.submit(_render_chunk, payload, digest, views, out_dir, width, height, outputs,
                          precision, threads, count, pure=False,
                          key=f"lanecast-views-{digest[:12]}-{chunk[0]}-{uuid.uuid4().hex[:8]}")
        futures[f] = chunk

    done, failed = [], {}
    for f in distributed.as_completed(list(futures)):
        try:
            d, s, fl = f.result()
        except Exception as e:  # the task itself failed (a worker lost too often, ...)
            for v in futures[f]:
                failed[v] = f"{type(e).__name__}: {e}"
            continue
        done += d
        skipped += s
        failed.update(fl)
    return Summary(done=sorted(done), skipped=sorted(skipped), failed=dict(sorted(failed.items())))
