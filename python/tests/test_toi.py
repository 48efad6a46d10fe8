"""revdist.time_of_impact: the analytic first contact of two balls inside the certified
interval, the same answers as `revdist toi --json` (same bits), batches equal to single
motions at any thread count, both pose layouts, and clear errors."""

import json
import subprocess

import numpy as np
import pytest

import revdist

# Ball of radius 0.75 centred at z = 0.75 in its own frame (`revdist models`: sphere).
R = 0.75


def row(t, q=(1.0, 0.0, 0.0, 0.0)):
    return np.array([*t, *q], dtype=np.float64)


def matrix(p):
    """(7,) row -> (4, 4) homogeneous matrix."""
    w, x, y, z = p[3:]
    m = np.eye(4)
    m[:3, :3] = [
        [1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
        [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
        [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)],
    ]
    m[:3, 3] = p[:3]
    return m


@pytest.fixture(scope="module")
def balls():
    s = revdist.Solid.model("sphere", eps=1e-4)
    return s, s


def test_analytic_ball_contact_inside_the_interval(balls):
    a, b = balls
    # B's centre from x = 4 to x = x1 (same height); contact when the centres are 2R + D apart.
    x1 = np.linspace(-1.0, 1.0, 9)
    starts = np.array([row((4.0, 0.0, 0.0))] * len(x1))
    ends = np.array([row((x, 0.0, 0.0)) for x in x1])
    for d in (0.0, 0.05):
        r = revdist.time_of_impact(a, b, starts, ends, contact_distance=d)
        exact = (4.0 - (2 * R + d)) / (4.0 - x1)
        assert list(r.outcome) == ["contact"] * len(x1)
        assert np.all(r.t_lower <= exact + 1e-12)
        assert np.all(exact <= r.t_upper + 1e-12)
        assert np.all(r.t_upper - r.t_lower < 1e-2)
        assert np.all(r.queries >= 1)


def test_apart_and_single_pose_broadcast(balls):
    a, b = balls
    # Passes 2 units above A: never within 2R.
    r = revdist.time_of_impact(a, b, row((4.0, 0.0, 2.0)), row((-4.0, 0.0, 2.0)))
    assert len(r) == 1 and r.outcome[0] == "apart" and r.t_lower[0] == 1.0
    assert np.isnan(r.t_upper[0]) and np.all(np.isnan(r.point_a[0]))


def motions(n, seed=5):
    rng = np.random.default_rng(seed)
    starts, ends = [], []
    for _ in range(n):
        u = rng.normal(size=3)
        u /= np.linalg.norm(u)
        q0 = rng.normal(size=4)
        q1 = rng.normal(size=4)
        starts.append(row(u * rng.uniform(2.5, 3.5), q0 / np.linalg.norm(q0)))
        ends.append(row(-u * rng.uniform(0.0, 0.5), q1 / np.linalg.norm(q1)))
    return np.array(starts), np.array(ends)


def test_batch_equals_single_motions_and_threads():
    a = revdist.Solid.model("pawn", eps=1e-3)
    b = revdist.Solid.model("cup", eps=1e-3)
    s, e = motions(6)
    batch = revdist.time_of_impact(a, b, s, e)
    one = revdist.time_of_impact(a, b, s, e, threads=1)
    mats = revdist.time_of_impact(
        a, b, np.array([matrix(p) for p in s]), np.array([matrix(p) for p in e]), threads=2
    )
    for i in range(len(s)):
        single = revdist.time_of_impact(a, b, s[i], e[i])
        for r in (batch, one):
            assert r.outcome[i] == single.outcome[0]
            assert r.t_lower[i] == single.t_lower[0]
            np.testing.assert_array_equal(r.t_upper[i], single.t_upper[0])
            assert r.queries[i] == single.queries[0]
        # Matrices round-trip through a rotation matrix: same motion up to rounding.
        assert mats.outcome[i] == single.outcome[0]
        assert abs(mats.t_lower[i] - single.t_lower[0]) < 1e-6


def test_same_bits_as_the_command_line(cli):
    a = revdist.Solid.model("pawn", eps=1e-3)
    b = revdist.Solid.model("cup", eps=1e-3)
    s, e = motions(3, seed=11)
    r = revdist.time_of_impact(a, b, s, e, contact_distance=0.01)
    for i in range(len(s)):
        pose = lambda p: json.dumps({"translation": list(p[:3]), "rotation": list(p[3:])})
        out = subprocess.run(
            [cli, "toi", "pawn", "cup", "--eps", "0.001", "--contact-distance", "0.01",
             "--pose-b", pose(s[i]), "--pose-b-end", pose(e[i]), "--json"],
            check=True, capture_output=True, text=True,
        )
        want = json.loads(out.stdout)
        assert r.outcome[i] == want["outcome"]
        assert r.t_lower[i] == want["t_lower"]
        if want["t_upper"] is None:
            assert np.isnan(r.t_upper[i])
        else:
            assert r.t_upper[i] == want["t_upper"]
            assert list(r.point_a[i]) == want["point_a"]
        assert r.queries[i] == want["queries"]


def test_eps_rebuilds_the_trees(balls):
    a = revdist.Solid.model("pawn", eps=1e-4)
    b = revdist.Solid.model("cup", eps=1e-4)
    s, e = motions(2, seed=3)
    coarse = revdist.time_of_impact(a, b, s, e, eps=1e-2)
    again = revdist.time_of_impact(
        revdist.Solid.model("pawn", eps=1e-2), revdist.Solid.model("cup", eps=1e-2), s, e
    )
    np.testing.assert_array_equal(coarse.t_lower, again.t_lower)


def test_errors(balls):
    a, b = balls
    s, e = motions(3)
    with pytest.raises(ValueError, match="pose_b_end holds 2 poses but pose_b_start holds 3"):
        revdist.time_of_impact(a, b, s, e[:2])
    with pytest.raises(ValueError, match="threads must be at least 1"):
        revdist.time_of_impact(a, b, s, e, threads=0)
    with pytest.raises(ValueError, match="contact_distance"):
        revdist.time_of_impact(a, b, s, e, contact_distance=-1.0)
    with pytest.raises(ValueError, match="pose_b_start"):
        revdist.time_of_impact(a, b, np.zeros((3, 5)), e)
    bad = s.copy()
    bad[1, 0] = np.nan
    with pytest.raises(ValueError, match=r"pose_b_start\[1\]"):
        revdist.time_of_impact(a, b, bad, e)
