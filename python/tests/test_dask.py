"""examples/python/dask_poses.py on a 2-worker LocalCluster (worker processes, so the solids
really travel pickled): 20,000 poses in chunks, merged, bit for bit the one-process answers."""

import importlib.util
import pathlib

import numpy as np
import pytest

import revdist

distributed = pytest.importorskip("distributed")

EXAMPLE = pathlib.Path(__file__).resolve().parents[2] / "examples" / "python" / "dask_poses.py"


def load_example():
    spec = importlib.util.spec_from_file_location("dask_poses", EXAMPLE)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_dask_answers_are_one_process_answers():
    ex = load_example()
    a = revdist.Solid.model("pawn", eps=1e-3)
    # A profile given as arrays travels by its pieces.
    b = revdist.Solid.from_nurbs(revdist.Solid.model("cup", eps=1e-3).profile(), eps=1e-3)
    poses = ex.random_poses(20_000, seed=3)
    with distributed.LocalCluster(
        n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None
    ) as cluster, distributed.Client(cluster) as client:
        got, _ = ex.distributed_answers(client, a, b, poses, chunk=1_500)
        workers = client.scheduler_info()["workers"]
        assert len(workers) == 2
    r = revdist.distance(a, b, poses)
    want = {k: getattr(r, k) for k in ex.FIELDS}
    assert len(got["value"]) == 20_000
    assert ex.identical(got, want)
    # The check can fail: one changed bit is seen.
    got["upper"][12_345] = np.nextafter(got["upper"][12_345], np.inf)
    assert not ex.identical(got, want)


def test_the_example_runs_end_to_end(tmp_path):
    ex = load_example()
    out = tmp_path / "dask.json"
    assert ex.main(["--n", "3000", "--chunk", "700", "--json", str(out)]) == 0
    assert '"identical_to_one_process": true' in out.read_text()
