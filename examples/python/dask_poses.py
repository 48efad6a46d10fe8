"""Certified distances for many poses spread over a Dask cluster, merged, and checked bit for
bit against one process.

The two solids are pickled once to every worker (a Solid pickles by its recipe and is
rebuilt there to the same tree), the poses go out in chunks, each chunk is answered by
``revdist.distance`` on a worker (cold queries, so an answer does not depend on which
worker ran it or in what order), and the chunks come back in order. The merged arrays are
then compared with ``revdist.distance`` run on all the poses in this process.

    python examples/python/dask_poses.py                       # a LocalCluster, 2 workers
    python examples/python/dask_poses.py --workers 4 --n 200000
    python examples/python/dask_poses.py --scheduler tcp://HOST:8786   # a running cluster

Against a real cluster: start ``dask scheduler`` on one machine and ``dask worker
tcp://HOST:8786 --nthreads 1`` on each of the others (or use dask-jobqueue's SLURMCluster),
with the same revdist wheel installed everywhere (``pip install revdist-*.whl``); then pass
``--scheduler``. Needs ``pip install "dask[distributed]"``.
"""

import argparse
import json
import sys
import time

import numpy as np

import revdist

# The fields merged and compared (the rest of a DistanceResult follows from the same query).
FIELDS = ("value", "lower", "upper", "point_a", "point_b", "overlap", "width_limit")


def random_poses(n, seed, spread=1.5):
    """``n`` seeded poses: translations uniform in a cube of half-side ``spread``, rotations
    uniform (normalised Gaussian quaternions)."""
    rng = np.random.default_rng(seed)
    t = rng.uniform(-spread, spread, (n, 3))
    q = rng.normal(size=(n, 4))
    q /= np.linalg.norm(q, axis=1)[:, None]
    return np.hstack([t, q])


def merge(results):
    """The chunks' DistanceResults, in order, as one dict of arrays."""
    return {k: np.concatenate([getattr(r, k) for r in results]) for k in FIELDS}


def identical(x, y):
    """Bit for bit: floats compared as their bit patterns (NaN and -0.0 included)."""
    for k in FIELDS:
        a, b = np.asarray(x[k]), np.asarray(y[k])
        if a.dtype.kind == "f":
            a, b = a.view(np.uint64), b.view(np.uint64)
        if a.shape != b.shape or not np.array_equal(a, b):
            return False
    return True


def distributed_answers(client, a, b, poses, chunk, tolerance=None):
    """Every pose's answer, computed in chunks of ``chunk`` poses on ``client``'s workers and
    merged in order; and the wall time of the computation (the solids' transfer included)."""
    t0 = time.perf_counter()
    a_f, b_f = client.scatter([a, b], broadcast=True)
    # revdist.distance itself runs on the workers (nothing of this file needs to be there),
    # on the worker's own thread: the cluster's threads are the parallelism.
    futures = [
        client.submit(
            revdist.distance, a_f, b_f, poses[i : i + chunk], tolerance=tolerance, threads=1, pure=False
        )
        for i in range(0, len(poses), chunk)
    ]
    merged = merge(client.gather(futures))
    return merged, time.perf_counter() - t0


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--a", default="pawn", help="solid A: a built-in name or a profile file")
    p.add_argument("--b", default="cup", help="solid B: a built-in name or a profile file")
    p.add_argument("--eps", type=float, default=1e-3, help="bound of both biarc trees")
    p.add_argument("--n", type=int, default=20_000, help="poses")
    p.add_argument("--chunk", type=int, default=2_000, help="poses per task")
    p.add_argument("--seed", type=int, default=1)
    p.add_argument("--workers", type=int, default=2, help="LocalCluster workers (processes)")
    p.add_argument("--threads-per-worker", type=int, default=1)
    p.add_argument("--scheduler", help="address of a running scheduler (tcp://HOST:8786) instead of a LocalCluster")
    p.add_argument("--json", help="write the measurement to this file")
    args = p.parse_args(argv)
    if args.n < 1 or args.chunk < 1:
        p.error("--n and --chunk must be at least 1")

    from dask.distributed import Client, LocalCluster

    a = revdist.Solid.load(args.a, eps=args.eps)
    b = revdist.Solid.load(args.b, eps=args.eps)
    poses = random_poses(args.n, args.seed)

    if args.scheduler:
        cluster, client = None, Client(args.scheduler)
    else:
        cluster = LocalCluster(
            n_workers=args.workers,
            threads_per_worker=args.threads_per_worker,
            processes=True,
            dashboard_address=None,
        )
        client = Client(cluster)
    try:
        workers = len(client.scheduler_info()["workers"])
        got, dask_s = distributed_answers(client, a, b, poses, args.chunk)
    finally:
        client.close()
        if cluster is not None:
            cluster.close()

    t0 = time.perf_counter()
    r = revdist.distance(a, b, poses, threads=1)
    one_s = time.perf_counter() - t0
    want = {k: getattr(r, k) for k in FIELDS}
    same = identical(got, want)
    report = {
        "a": args.a,
        "b": args.b,
        "eps": args.eps,
        "poses": args.n,
        "chunk": args.chunk,
        "workers": workers,
        "dask_seconds": dask_s,
        "dask_poses_per_second": args.n / dask_s,
        "one_thread_seconds": one_s,
        "one_thread_poses_per_second": args.n / one_s,
        "identical_to_one_process": same,
    }
    print(
        f"{args.a}-{args.b} eps {args.eps}: {args.n} poses in chunks of {args.chunk} on "
        f"{workers} Dask workers: {dask_s:.2f} s ({args.n / dask_s:,.0f} poses/s); "
        f"one process, one thread: {one_s:.2f} s ({args.n / one_s:,.0f} poses/s); "
        f"identical bits: {same}"
    )
    if args.json:
        with open(args.json, "w") as f:
            json.dump(report, f, indent=1)
    return 0 if same else 1


if __name__ == "__main__":
    sys.exit(main())
