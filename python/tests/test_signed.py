"""signed=True: the signed distance and the certified penetration depth of overlapping
solids, checked against an exact case (two balls: PD = r1 + r2 - |c1 - c2|, and the
translation along pd_direction that must separate them), against the command line's
`distance --batch` with `"signed": true` (the same bits), and for the GIL, the warm start
and the result's shapes."""

import json
import subprocess
import threading
import time

import numpy as np
import pytest

import revdist
from conftest import random_poses

S = 0.7071067811865476  # weight of a rational quadratic quarter circle


def ball(r, eps):
    """A ball of radius r centred on its frame's origin: two exact rational quarter arcs."""
    return revdist.Solid.from_nurbs(
        [
            (2, [0, 0, 0, 1, 1, 1], [[0, -r], [r, -r], [r, 0]], [1.0, S, 1.0]),
            (2, [0, 0, 0, 1, 1, 1], [[r, 0], [r, r], [0, r]], [1.0, S, 1.0]),
        ],
        eps=eps,
        name=f"ball{r}",
    )


def bits(x):
    return np.asarray(x, dtype=np.float64).view(np.uint64)


def ball_poses(rng, n, r1, r2):
    """B's poses (rotations uniform) with centre distances spread over (0, r1 + r2): crossing
    balls, B nested in A, and a share apart (up to 1.2 (r1 + r2))."""
    d = rng.uniform(0.0, 1.2 * (r1 + r2), n)
    u = rng.normal(size=(n, 3))
    u /= np.linalg.norm(u, axis=1)[:, None]
    q = rng.normal(size=(n, 4))
    q /= np.linalg.norm(q, axis=1)[:, None]
    return np.hstack([u * d[:, None], q]), d


@pytest.mark.parametrize("r1,r2,eps", [(0.5, 0.3, 1e-3), (0.4, 0.4, 1e-4), (0.6, 0.1, 1e-4)])
def test_two_balls_exact_depth(r1, r2, eps):
    """PD of two balls is r1 + r2 - |c1 - c2| (B must move its centre to distance r1 + r2):
    inside [pd_lower, pd_upper]; B moved by pd_upper along pd_direction is apart (its centre
    at distance >= r1 + r2, computed here); the signed interval holds d - r1 - r2 on both
    sides of contact; and the width meets the target of a ball against a solid, max(2
    (eps_a + eps_b), 5 % of PD). Tolerance 1e-12: the exact depth's own rounding (a few ulps
    of 1) and the quarter arc's weight rounded to a double (an error of 1e-16 of r)."""
    a, b = ball(r1, eps), ball(r2, eps)
    rng = np.random.default_rng(int(1e6 * (r1 + r2 + eps)))
    poses, d = ball_poses(rng, 200, r1, r2)
    res = revdist.distance(a, b, poses, signed=True)
    exact = r1 + r2 - d
    tol = 1e-12
    over = exact > tol
    apart = exact < -tol
    assert over.sum() > 100 and apart.sum() > 10
    # The signed distance d - r1 - r2 = -PD when overlapping.
    assert np.all(res.signed_lower <= -exact + tol), np.max(res.signed_lower + exact)
    assert np.all(res.signed_upper >= -exact - tol), np.min(res.signed_upper + exact)
    # The depth.
    lo, hi = res.pd_lower[over], res.pd_upper[over]
    assert np.all(lo <= exact[over] + tol), np.max(lo - exact[over])
    assert np.all(hi >= exact[over] - tol), np.min(hi - exact[over])
    assert np.all(lo > 0.0)
    width = hi - lo
    target = np.maximum(2 * (2 * eps), 0.05 * exact[over])
    assert np.all(width <= target), (width / target).max()
    # B moved by pd_upper along pd_direction: its centre at distance >= r1 + r2 from A's.
    u = res.pd_direction[over]
    assert np.allclose(np.linalg.norm(u, axis=1), 1.0, atol=1e-12)
    moved = poses[over, :3] + u * hi[:, None]
    assert np.all(np.linalg.norm(moved, axis=1) >= r1 + r2 - tol)
    # Apart: depth [0, 0], no direction, the signed distance is the distance.
    assert np.all(res.pd_lower[apart] == 0.0) and np.all(res.pd_upper[apart] == 0.0)
    assert np.all(res.pd_direction[apart] == 0.0)
    assert np.array_equal(bits(res.signed_lower[apart]), bits(res.lower[apart]))
    assert np.array_equal(bits(res.signed_upper[apart]), bits(res.upper[apart]))


def test_signed_gradient_of_two_balls():
    """Overlapping balls: the signed distance d - r1 - r2 has gradient n (unit, A's centre to
    B's) in B's translation; the answer's is pd_direction, certified to separate within
    pd_upper, which pins its angle to n: moving B by s along a unit g at angle theta to n
    separates once s >= s(theta) = -d cos(theta) + sqrt(R^2 - d^2 sin^2(theta)) (R = r1 +
    r2), and s(theta) - PD >= d (1 - cos(theta)) (1 - 2 d / R), so
    |g - n|^2 = 2 (1 - cos(theta)) <= 2 (pd_upper - PD) / (d (1 - 2 d / R)) for d < R / 2.
    The rotation part (contact_b - origin_b) x g is perpendicular to g."""
    r1, r2 = 0.5, 0.3
    big_r = r1 + r2
    a, b = ball(r1, 1e-4), ball(r2, 1e-4)
    poses, d = ball_poses(np.random.default_rng(11), 300, r1, r2)
    keep = (d > 0.02) & (d < 0.45 * big_r)
    res = revdist.distance(a, b, poses[keep], signed=True)
    d = d[keep]
    n = poses[keep, :3] / d[:, None]
    g = res.gradient_translation
    given = ~np.isnan(g).any(axis=1)
    assert given.sum() > 0.9 * keep.sum(), (given.sum(), keep.sum())
    excess = res.pd_upper - (big_r - d)
    bound = 2 * excess / (d * (1 - 2 * d / big_r)) + 1e-12
    err = ((g - n) ** 2).sum(axis=1)
    assert np.all(err[given] <= bound[given]), (err / bound)[given].max()
    assert np.array_equal(g[given], res.pd_direction[given])
    rot = res.gradient_rotation[given]
    assert np.abs((rot * g[given]).sum(axis=1)).max() < 1e-12


def run_batch(cli, lines):
    text = "".join(json.dumps(line) + "\n" for line in lines)
    out = subprocess.run(
        [cli, "distance", "--batch", "-"], input=text, capture_output=True, text=True, check=False
    )
    assert out.returncode in (0, 1), out.stderr
    answers = [json.loads(line) for line in out.stdout.splitlines()]
    assert len(answers) == len(lines)
    return answers


PAIRS = [("pawn", "cup", 1e-3), ("sphere", "capsule", 1e-3), ("cone", "ring", 1e-4),
         ("bottle", "morph@0.3", 1e-3)]


def test_signed_is_the_cli(cli):
    """The same bits as `revdist distance --batch` lines with "signed": true: the distance's
    fields, the signed distance, the depth and its direction (zeros and 0 where the command
    line gives no "penetration": certified apart), and the signed distance's gradient."""
    rng = np.random.default_rng(20261128)
    overlapping, narrow = 0, 0
    for a, b, eps in PAIRS:
        poses = random_poses(rng, 30, 0.6, digits=9)
        lines = [
            {"a": a, "b": b, "eps": eps, "signed": True,
             "pose_b": {"translation": list(p[:3]), "rotation": list(p[3:])}}
            for p in poses
        ]
        want = run_batch(cli, lines)
        assert all("error" not in x for x in want), want[:2]
        sa, sb = revdist.Solid.model(a, eps=eps), revdist.Solid.model(b, eps=eps)
        r = revdist.distance(sa, sb, poses, signed=True)
        plain = revdist.distance(sa, sb, poses)
        for key in ("value", "lower", "upper", "point_a", "point_b"):
            assert np.array_equal(bits(getattr(r, key)), bits(getattr(plain, key))), key
        assert np.array_equal(bits(r.value), bits([x["distance"] for x in want]))
        for i, x in enumerate(want):
            s = x["signed_distance"]
            assert bits(r.signed_lower[i]) == bits(s["lower"]), (a, b, i)
            assert bits(r.signed_upper[i]) == bits(s["upper"]), (a, b, i)
            p = x.get("penetration")
            if p is None:
                assert r.pd_lower[i] == 0.0 and r.pd_upper[i] == 0.0, (a, b, i)
                assert np.all(r.pd_direction[i] == 0.0)
            else:
                overlapping += 1
                assert bits(r.pd_lower[i]) == bits(p["lower"]), (a, b, i)
                assert bits(r.pd_upper[i]) == bits(p["upper"]), (a, b, i)
                assert np.array_equal(bits(r.pd_direction[i]), bits(p["direction"]))
                assert r.pd_lower[i] <= r.pd_upper[i]
                # The lower bound's certificate: none exactly when nothing positive is.
                kinds = ("none", "point", "ball_covering", "translation_covering")
                assert p["certificate"] in kinds, p
                assert (p["certificate"] == "none") == (p["lower"] == 0.0), p
                covered = p["certificate"] == "translation_covering"
                assert p["cover_cells"] >= 0 and (not covered or p["cover_cells"] > 0), p
            g = x.get("gradient")
            if g is None:
                assert np.isnan(r.gradient_translation[i]).all(), (a, b, i)
            else:
                narrow += p is not None
                assert np.array_equal(bits(r.gradient_translation[i]), bits(g["translation"]))
                assert np.array_equal(bits(r.gradient_rotation[i]), bits(g["rotation"]))
    # Both kinds of answer were compared, and gradients of overlapping pairs.
    assert 20 < overlapping < len(PAIRS) * 30, overlapping
    assert narrow > 0


def test_unsigned_results_have_no_signed_fields(pawn_cup):
    a, b = pawn_cup
    r = revdist.distance(a, b, np.array([0.3, 0.0, 0.2, 1, 0, 0, 0]))
    for key in ("signed_lower", "signed_upper", "pd_lower", "pd_upper", "pd_direction"):
        assert getattr(r, key) is None


def test_single_pose_gives_scalars(pawn_cup):
    a, b = pawn_cup
    r = revdist.distance(a, b, np.array([0.3, 0.0, 0.2, 1, 0, 0, 0]), signed=True)
    assert isinstance(r.pd_lower, float) and isinstance(r.signed_upper, float)
    assert r.pd_direction.shape == (3,)
    assert r.overlap and 0.0 < r.pd_lower <= r.pd_upper
    assert r.signed_lower == -r.pd_upper and r.signed_upper == -r.pd_lower


def test_pair_signed_is_cold_and_leaves_the_warm_start(pawn_cup):
    """Pair.distance(signed=True) gives the cold answers' bits, and the warm start after it
    is the one before it (a fresh Pair with the same unsigned calls gives the same bits)."""
    a, b = pawn_cup
    rng = np.random.default_rng(3)
    p1, p2, p3 = (random_poses(rng, 20, 0.5) for _ in range(3))
    pair, fresh = revdist.Pair(a, b), revdist.Pair(a, b)
    pair.distance(p1)
    s = pair.distance(p2, signed=True)
    cold = revdist.distance(a, b, p2, signed=True)
    for key in ("lower", "upper", "signed_lower", "signed_upper", "pd_lower", "pd_upper",
                "pd_direction"):
        assert np.array_equal(bits(getattr(s, key)), bits(getattr(cold, key))), key
    after = pair.distance(p3)
    fresh.distance(p1)
    want = fresh.distance(p3)
    assert np.array_equal(bits(after.lower), bits(want.lower))
    assert np.array_equal(bits(after.upper), bits(want.upper))


def test_signed_batch_releases_the_gil():
    """While a thread runs a signed batch (overlapping poses: the depth search runs), the
    main thread keeps executing bytecode (counts progress, not time)."""
    a, b = revdist.Solid.model("pawn", eps=1e-4), revdist.Solid.model("bottle", eps=1e-4)
    poses = random_poses(np.random.default_rng(8), 300, 0.3)
    done = threading.Event()

    def work():
        revdist.distance(a, b, poses, threads=1, signed=True)
        done.set()

    worker = threading.Thread(target=work)
    ticks = 0
    worker.start()
    time.sleep(0.005)
    while not done.is_set():
        ticks += 1
        time.sleep(0)
    worker.join()
    assert ticks > 100, ticks
