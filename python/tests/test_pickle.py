"""Solids and Pairs travel: pickled (as multiprocessing, Dask, Ray and joblib send them) they
are rebuilt from their recipe and answer with the same bits, in this process and in a
spawned one."""

import copy
import multiprocessing
import pickle

import numpy as np
import pytest

import revdist
from conftest import random_poses

KEYS = ("value", "lower", "upper", "point_a", "point_b", "gradient_translation")


def bits(x):
    return np.asarray(x, dtype=np.float64).view(np.uint64)


def answers(a, b, poses):
    r = revdist.distance(a, b, poses)
    return {k: getattr(r, k) for k in KEYS}


def assert_same_bits(got, want):
    for k in KEYS:
        assert np.array_equal(bits(got[k]), bits(want[k])), k


def solids(tmp_path):
    """One solid of each origin: a model by name, a morph frame, a file, a polyline and
    NURBS pieces (a rational one)."""
    cup = revdist.Solid.model("cup", eps=1e-3)
    path = tmp_path / "cup.toml"
    text = "\n".join(
        [
            'name = "half-ball"',
            "[[piece]]",
            "degree = 2",
            "knots = [0.0, 0.0, 0.0, 1.0, 1.0, 1.0]",
            "points = [[0.0, -1.0], [1.0, -1.0], [1.0, 0.0]]",
            "weights = [1.0, 0.7071067811865476, 1.0]",
            "[[piece]]",
            "degree = 1",
            "knots = [0.0, 0.0, 1.0, 1.0]",
            "points = [[1.0, 0.0], [0.0, 0.0]]",
        ]
    )
    path.write_text(text + "\n")
    return [
        revdist.Solid.model("pawn", eps=1e-4),
        revdist.Solid.load("morph@0.25", eps=1e-3),
        revdist.Solid.from_file(path, eps=1e-3),
        revdist.Solid.from_polyline([[0, -0.5], [0.6, -0.5], [0.3, 0.2], [0.6, 0.5], [0, 0.5]], eps=1e-3),
        revdist.Solid.from_nurbs(cup.profile(), eps=1e-3, name="cup-pieces"),
    ]


def test_pickled_solids_give_the_same_bits(tmp_path):
    b = revdist.Solid.model("bottle", eps=1e-3)
    poses = random_poses(np.random.default_rng(4242), 200, 1.5)
    for a in solids(tmp_path):
        for protocol in (2, pickle.HIGHEST_PROTOCOL):
            back = pickle.loads(pickle.dumps(a, protocol=protocol))
            assert (back.spec, back.eps, back.nodes, back.kind) == (a.spec, a.eps, a.nodes, a.kind)
            assert_same_bits(answers(back, b, poses), answers(a, b, poses))
            assert_same_bits(answers(b, back, poses), answers(b, a, poses))
            for x, y in zip(back.profile(), a.profile()):
                assert x["degree"] == y["degree"]
                assert np.array_equal(bits(x["knots"]), bits(y["knots"]))
                assert np.array_equal(bits(x["points"]), bits(y["points"]))


def test_a_file_solid_pickles_without_its_file(tmp_path):
    a = solids(tmp_path)[2]
    data = pickle.dumps(a)
    (tmp_path / "cup.toml").unlink()
    back = pickle.loads(data)
    poses = random_poses(np.random.default_rng(7), 50, 1.5)
    b = revdist.Solid.model("cup", eps=1e-3)
    assert_same_bits(answers(back, b, poses), answers(a, b, poses))


def test_copies_are_the_solid_itself():
    a = revdist.Solid.model("pawn", eps=1e-3)
    assert copy.copy(a) is a and copy.deepcopy(a) is a
    both = copy.deepcopy([a, a])
    assert both[0] is a and both[1] is a


def test_a_pickled_pair_starts_cold():
    a, b = revdist.Solid.model("pawn", eps=1e-3), revdist.Solid.model("cup", eps=1e-3)
    poses = random_poses(np.random.default_rng(11), 20, 1.5)
    pair = revdist.Pair(a, b)
    pair.distance(poses[:10])
    back = pickle.loads(pickle.dumps(pair))
    assert back.a.spec == "pawn" and back.b.spec == "cup"
    cold = revdist.distance(a, b, poses[10:])
    first = back.distance(poses[10])
    assert bits(first.value) == bits(cold.value[0]) and bits(first.upper) == bits(cold.upper[0])


def test_a_distance_result_pickles():
    a, b = revdist.Solid.model("pawn", eps=1e-3), revdist.Solid.model("cup", eps=1e-3)
    r = revdist.distance(a, b, random_poses(np.random.default_rng(3), 10, 1.5))
    back = pickle.loads(pickle.dumps(r))
    assert np.array_equal(bits(back.lower), bits(r.lower))
    assert list(back.width_limit) == list(r.width_limit)


def remote_answers(a, b, poses):
    """Run in a spawned process: the solids arrive pickled."""
    return answers(a, b, poses)


def test_solids_sent_to_spawned_processes_give_the_same_bits(tmp_path):
    ctx = multiprocessing.get_context("spawn")
    b = revdist.Solid.model("bottle", eps=1e-3)
    poses = random_poses(np.random.default_rng(99), 100, 1.5)
    work = [(a, b, poses) for a in solids(tmp_path)]
    with ctx.Pool(2) as pool:
        got = pool.starmap(remote_answers, work)
    for (a, _, _), g in zip(work, got):
        assert_same_bits(g, answers(a, b, poses))


def test_a_bad_recipe_is_a_value_error():
    with pytest.raises(ValueError, match="unknown solid recipe"):
        revdist._revdist._solid_from_recipe(("teapot", "x", 1e-3))
    with pytest.raises(ValueError, match="unknown model"):
        revdist._revdist._solid_from_recipe(("model", "teapot", 1e-3))
