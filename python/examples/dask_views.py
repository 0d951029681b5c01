# python/examples/dask_views.py: the same views on a Dask cluster; each view's .npy files go
# all or nothing into out/view_NNNNNN/, and a rerun skips the complete ones
import numpy as np
from distributed import Client, LocalCluster

import lanecast
import lanecast.dask


def main():
    scene = lanecast.Scene.load("scenes/bunny.sc")
    cams = [lanecast.Camera((20 * np.cos(a), 9, 20 * np.sin(a)), (0, 4.7, 0), fov=42)
            for a in np.linspace(0, 2 * np.pi, 24, endpoint=False)]
    # a cluster already running: `with Client("tcp://HOST:8786") as client:`
    with LocalCluster(n_workers=2, threads_per_worker=1) as cluster, Client(cluster) as client:
        print(lanecast.dask.render_views(client, scene, cams, "out", 640, 360))


if __name__ == "__main__":  # Dask's workers import this file: the work runs only here
    main()
