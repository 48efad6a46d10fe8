"""`Pair` along a motion: warm-started answers are certified like cold ones."""

import numpy as np

import revdist


def motion(n):
    """B circling A's axis at distances between touching and well apart, turning about a
    tilted axis: consecutive poses are close, as in a simulation."""
    s = np.linspace(0.0, 2.0 * np.pi, n)
    r = 0.9 + 0.25 * np.sin(3 * s)
    axis = np.array([0.3, 1.0, 0.2]) / np.linalg.norm([0.3, 1.0, 0.2])
    half = 0.5 * s
    q = np.column_stack([np.cos(half), np.sin(half)[:, None] * axis])
    return np.column_stack([r * np.cos(s), r * np.sin(s), 0.2 + 0.1 * np.cos(s), q])


def test_warm_starts_agree_with_cold_queries():
    a, b = revdist.Solid.model("pawn", eps=1e-4), revdist.Solid.model("cup", eps=1e-4)
    poses = motion(150)
    cold = revdist.distance(a, b, poses)
    pair = revdist.Pair(a, b)
    warm_1 = pair.distance(poses[:70])
    warm_2 = pair.distance(poses[70:])  # continues from the last pose of the first call
    for key in ("value", "lower", "upper"):
        assert len(getattr(warm_1, key)) + len(getattr(warm_2, key)) == 150
    lower = np.concatenate([warm_1.lower, warm_2.lower])
    upper = np.concatenate([warm_1.upper, warm_2.upper])
    value = np.concatenate([warm_1.value, warm_2.value])
    # Both intervals hold the true distance, so they meet; each value is realised by a
    # pair of points, so it is at least the other's lower bound.
    assert np.all(np.maximum(lower, cold.lower) <= np.minimum(upper, cold.upper))
    assert np.all(value >= cold.lower) and np.all(cold.value >= lower)
    assert np.all(upper - lower <= 2e-4 + 1e-12)
    # The first pose after reset is a cold query: the same bits as `distance`.
    pair.reset()
    first = pair.distance(poses[0])
    assert first.value == cold.value[0] and first.lower == cold.lower[0]
    # Errors stop the motion with the pose's message.
    bad = poses[:3].copy()
    bad[1, 3] = 2.0
    try:
        pair.distance(bad)
    except ValueError as e:
        assert str(e).startswith("poses[1]: rotation")
    else:
        raise AssertionError("a non-unit quaternion was accepted")


def test_warm_start_refuses_threads():
    """The extension's one entry point runs a warm-started motion on the calling thread:
    asking it for threads as well is refused rather than ignored."""
    a, b = revdist.Solid.model("pawn", eps=1e-4), revdist.Solid.model("cup", eps=1e-4)
    pair = revdist._revdist.Pair(a, b)
    p = np.array([2.0, 0, 0, 1, 0, 0, 0])
    try:
        pair.distance(p, threads=2)
    except ValueError as e:
        assert "runs in order on the calling thread" in str(e)
    else:
        raise AssertionError("threads were accepted with a warm start")
    assert pair.distance(p, threads=2, warm=False)["value"] == pair.distance(p)["value"]
