"""Profiles from numpy arrays: polylines and NURBS pieces, checked against analytic
distances, against the same profile read from a file (same bits, same error messages), and
against malformed input (a ValueError naming the problem, never a crash)."""

import numpy as np
import pytest

import revdist
from conftest import random_poses

CYLINDER = np.array([[0.0, -1.0], [1.0, -1.0], [1.0, 1.0], [0.0, 1.0]])  # radius 1, z in [-1, 1]
RING = np.array([[2.0, -0.5], [3.0, -0.5], [3.0, 0.5], [2.0, 0.5], [2.0, -0.5]])  # closed


def bits(x):
    return np.asarray(x, dtype=np.float64).view(np.uint64)


def test_polylines_give_the_analytic_distances():
    """Cylinders and a square ring made of segments, at poses whose distance is exact: the
    certified interval holds it and is at most eps_a + eps_b wide."""
    eps = 1e-4
    cyl = revdist.Solid.from_polyline(CYLINDER, eps=eps)
    ring = revdist.Solid.from_polyline(RING, eps=eps)
    assert (cyl.kind, ring.kind) == ("open", "closed")
    s = np.sqrt(0.5)
    cases = [
        (cyl, cyl, [3.0, 0.0, 0.3, 1, 0, 0, 0], 1.0),  # side to side, parallel axes
        (cyl, cyl, [0.0, 0.0, 2.5, 1, 0, 0, 0], 0.5),  # top face to bottom face
        (cyl, cyl, [0.2, 0.1, 2.5, s, s, 0, 0], 0.5),  # top face to a lying cylinder's side
        (ring, cyl, [0.0, 0.0, 0.0, 1, 0, 0, 0], 1.0),  # a cylinder in the ring's hole
        (ring, cyl, [0.4, -0.3, 0.2, 1, 0, 0, 0], 0.5),  # moved towards the ring by 0.5
        (cyl, cyl, [1.5, 0.0, 0.0, 1, 0, 0, 0], 0.0),  # overlapping
    ]
    for a, b, pose, want in cases:
        r = revdist.distance(a, b, np.array(pose, float))
        assert r.lower <= want <= r.upper, (pose, r)
        assert r.upper - r.lower <= 2 * eps + 1e-12
        assert r.overlap == (want == 0.0)


def test_corners_of_a_polyline_are_kept():
    """A cone from a polyline (an apex on the axis, a rim corner): sampled points of its
    tessellation lie within eps of the exact surface."""
    cone = revdist.Solid.from_polyline([[0.0, 0.0], [1.0, 0.0], [0.0, 2.0]], eps=1e-4)
    v, _ = cone.tessellate(1e-3)
    rho, z = np.hypot(v[:, 0], v[:, 1]), v[:, 2]
    # Distance to the triangle (0,0)-(1,0)-(0,2) boundary in the (rho, z) plane.
    side = np.abs(2 * rho + z - 2) / np.sqrt(5)
    d = np.minimum(np.minimum(side, np.abs(z)), np.abs(rho))
    assert d.max() <= 1e-3 + 1e-12
    assert z.max() > 2.0 - 1e-3 and rho.max() > 1.0 - 1e-3


def quarter_disk_toml():
    return "\n".join(
        [
            'name = "quarter-disk"',
            "[[piece]]",
            "degree = 2",
            "knots = [0.0, 0.0, 0.0, 1.0, 1.0, 1.0]",
            "points = [[0.0, -1.0], [1.0, -1.0], [1.0, 0.0]]",
            "weights = [1.0, 0.7071067811865476, 1.0]",
            "[[piece]]",
            "degree = 1",
            "knots = [0.0, 0.0, 1.0, 1.0]",
            "points = [[1.0, 0.0], [0.0, 0.0]]",
            "",
        ]
    )


QUARTER_DISK = [
    {"degree": 2, "knots": [0, 0, 0, 1, 1, 1], "points": [[0, -1], [1, -1], [1, 0]],
     "weights": [1.0, 0.7071067811865476, 1.0]},
    (1, np.array([0.0, 0.0, 1.0, 1.0]), np.array([[1.0, 0.0], [0.0, 0.0]])),
]


def test_nurbs_pieces_are_the_profile_file(tmp_path):
    path = tmp_path / "q.toml"
    path.write_text(quarter_disk_toml())
    from_file = revdist.Solid.from_file(path, eps=1e-4)
    from_arrays = revdist.Solid.from_nurbs(QUARTER_DISK, eps=1e-4)
    b = revdist.Solid.model("pawn", eps=1e-4)
    poses = random_poses(np.random.default_rng(5), 100, 1.5)
    x, y = revdist.distance(from_file, b, poses), revdist.distance(from_arrays, b, poses)
    for key in ("value", "lower", "upper", "point_a", "point_b"):
        assert np.array_equal(bits(getattr(x, key)), bits(getattr(y, key))), key
    # A lower half ball of radius 1 (z in [-1, 0]); the copy 3 below: flat face at z = -3
    # to the lowest point z = -1.
    r = revdist.distance(from_arrays, from_arrays, np.array([0.0, 0.0, -3.0, 1, 0, 0, 0]))
    assert r.lower <= 2.0 <= r.upper


def test_profile_round_trips_every_model():
    """profile() gives the pieces bit for bit: rebuilt by from_nurbs, the same answers."""
    b = revdist.Solid.model("cup", eps=1e-3)
    poses = random_poses(np.random.default_rng(8), 30, 1.5)
    for name in revdist.models():
        a = revdist.Solid.model(name, eps=1e-3)
        pieces = a.profile()
        assert all(p["points"].shape[1] == 2 and p["points"].dtype == np.float64 for p in pieces)
        back = revdist.Solid.from_nurbs(pieces, eps=1e-3, name=name)
        assert back.kind == a.kind and back.nodes == a.nodes, name
        x, y = revdist.distance(a, b, poses), revdist.distance(back, b, poses)
        assert np.array_equal(bits(x.upper), bits(y.upper)), name


def piece_toml(pieces):
    out = ['name = "p"']
    for degree, knots, points in pieces:
        out += ["[[piece]]", f"degree = {degree}", f"knots = {knots}", f"points = {points}"]
    return "\n".join(out) + "\n"


# Bad pieces in both forms: what a profile file says after its "piece k (line l): " or
# "profile file '...': ", from_nurbs says after "piece k: " or directly.
BAD_PIECES = [
    # Self-intersection: a bow tie.
    [(1, [0.0, 0.0, 1.0, 1.0], [[0.0, 0.0], [1.0, 1.0]]),
     (1, [0.0, 0.0, 1.0, 1.0], [[1.0, 1.0], [1.0, 0.0]]),
     (1, [0.0, 0.0, 1.0, 1.0], [[1.0, 0.0], [0.0, 1.0]])],
    # Off the half-plane.
    [(1, [0.0, 0.0, 1.0, 1.0], [[0.0, 0.0], [-1.0, 1.0]]),
     (1, [0.0, 0.0, 1.0, 1.0], [[-1.0, 1.0], [0.0, 2.0]])],
    # Not closed, not on the axis.
    [(1, [0.0, 0.0, 1.0, 1.0], [[1.0, 0.0], [2.0, 1.0]])],
    # A wrong knot count; decreasing knots.
    [(1, [0.0, 0.0, 1.0], [[0.0, 0.0], [1.0, 1.0]])],
    [(1, [0.0, 1.0, 0.5, 1.0], [[0.0, 0.0], [1.0, 1.0]])],
]


@pytest.mark.parametrize("pieces", BAD_PIECES)
def test_bad_pieces_have_the_profile_files_messages(tmp_path, pieces):
    path = tmp_path / "bad.toml"
    path.write_text(piece_toml(pieces))
    with pytest.raises(ValueError) as file_error:
        revdist.Solid.from_file(path)
    with pytest.raises(ValueError) as array_error:
        revdist.Solid.from_nurbs(pieces)
    file_msg, array_msg = str(file_error.value), str(array_error.value)
    file_msg = file_msg.split(f"profile file '{path}': ", 1)[1]
    if file_msg.startswith("piece"):
        head, rest = file_msg.split("): ", 1)
        file_msg = head.split(" (line")[0] + ": " + rest
    assert array_msg == file_msg


@pytest.mark.parametrize(
    "rz, message",
    [
        ([[0, 0], [1, 0], [1, 1], [2, -1], [0, 1.5]], "must not cross, touch or fold back"),
        ([[0, 0], [1, 0], [np.nan, 1], [0, 1]], "rz[2] = [NaN, 1] is not a finite point"),
        ([[0, 0], [1, 0], [np.inf, 1], [0, 1]], "rz[2] = [inf, 1] is not a finite point"),
        ([[1, 0], [2, 0], [2, 1]], "a closed polyline repeats its first point at the end"),
        ([[0, 0], [-1, 0], [0, 1]], "rho = -1e0 < 0"),
        ([[0, 0], [1, 0], [1, 0], [0, 1]], "piece 1 has length 0e0"),
        ([[2, 0], [3, 0], [3, 1], [0, 1], [2, 0]], "closed profile touches the axis"),
        (np.zeros((3, 3)), "rz must have shape (n, 2), rows [rho, z]; got shape (3, 3)"),
        (np.zeros((2, 2, 2)), "got shape (2, 2, 2)"),
        ([[0, 0]], "a polyline needs at least 2 points, got 1"),
        ([], "got shape (0,)"),
        ("abc", "rz must be real numbers (float64), got dtype <U3"),
        ([[0, 0], [1, 0, 2]], "rz: not an array of numbers"),
        (np.array([[0, 0], [1j, 1]]), "got dtype complex128"),
        ([[0, 0], [1e200, 0], [0, 1]], "outside the representable range"),
        ([[0, 0], [2**60, 0], [0, 1]], "integers beyond 2**53"),
    ],
)
def test_bad_polylines_name_the_problem(rz, message):
    with pytest.raises(ValueError) as e:
        revdist.Solid.from_polyline(rz, eps=1e-3)
    assert message in str(e.value)


@pytest.mark.parametrize(
    "pieces, message",
    [
        ({"degree": 1}, "got one dict"),
        (5, "pieces must be a list of pieces"),
        ([], "a profile needs at least one piece"),
        ([5], "piece 0: expected a dict or a sequence"),
        ([(1, [0, 0, 1, 1])], "has 3 or 4 items, got 2"),
        ([{"degree": 1, "knots": [0, 0, 1, 1]}], "piece 0: missing field 'points'"),
        ([{"degree": 1, "knots": [0, 0, 1, 1], "points": [[0, 0], [1, 1]], "colour": 1}],
         "piece 0: unknown field 'colour'"),
        ([{1: 2}], "field names must be strings"),
        ([(1.5, [0, 0, 1, 1], [[0, 0], [0, 1]])], "degree must be a whole number >= 1, got 1.5"),
        ([(-1, [0, 0, 1, 1], [[0, 0], [0, 1]])], "degree must be a whole number >= 1, got -1"),
        ([(0, [0, 1], [[0, 0]])], "piece 0: degree must be at least 1"),
        ([(1, [[0, 0, 1, 1]], [[0, 0], [0, 1]])], "piece 0: knots must be one-dimensional"),
        ([(1, [0, 0, 1, 1], [0, 0, 0, 1])], "piece 0: points must have shape (n, 2)"),
        ([(1, [0, 0, 1, 1], [[0, 0], [0, 1]], [1, -1])], "piece 0: weight 1 is -1"),
        ([(1, [0, 0, 1, 1], [[0, 0], [0, 1]], [1])], "piece 0: 2 control points but 1 weights"),
        ([(1, [0, 0, 1, 1], [[0, 0], [0, np.nan]])], "piece 0: control point 1 is not finite"),
        ([(1, [0, 0, np.nan, 1], [[0, 0], [0, 1]])], "piece 0: knot 2 is not finite"),
        ([(1, [0, 0, 1, 1], [[0, 0], [1, 1]]), (1, [0, 0, 1, 1], [[1, 1.5], [0, 2]])],
         "gap of 5e-1 between the end of piece 0 and the start of piece 1"),
    ],
)
def test_bad_nurbs_name_the_problem(pieces, message):
    with pytest.raises(ValueError) as e:
        revdist.Solid.from_nurbs(pieces, eps=1e-3)
    assert message in str(e.value)


def test_bad_eps_is_a_value_error():
    for eps in (0.0, -1.0, np.nan, 10.0):
        with pytest.raises(ValueError):
            revdist.Solid.from_polyline(CYLINDER, eps=eps)
        with pytest.raises(ValueError):
            revdist.Solid.from_nurbs(QUARTER_DISK, eps=eps)


def test_random_garbage_never_crashes():
    """Random polylines and pieces, mostly invalid: each is a Solid or a ValueError (a panic
    would surface as pyo3's PanicException, a BaseException, and fail the test)."""
    rng = np.random.default_rng(2024)
    built = refused = 0
    for _ in range(300):
        n = int(rng.integers(1, 8))
        rz = rng.normal(size=(n, 2)) * rng.choice([1e-13, 1.0, 1e120])
        if rng.random() < 0.5:
            rz[0, 0] = rz[-1, 0] = 0.0
        if rng.random() < 0.2:
            rz[rng.integers(n), rng.integers(2)] = rng.choice([np.nan, np.inf])
        try:
            revdist.Solid.from_polyline(np.abs(rz) if rng.random() < 0.7 else rz, eps=1e-3)
            built += 1
        except ValueError:
            refused += 1
        degree = int(rng.integers(0, 4))
        k = int(rng.integers(0, 8))
        knots = np.sort(rng.random(k)) if rng.random() < 0.8 else rng.random(k)
        pts = np.abs(rng.normal(size=(int(rng.integers(0, 6)), 2)))
        weights = rng.normal(size=len(pts)) if rng.random() < 0.3 else None
        try:
            revdist.Solid.from_nurbs([(degree, knots, pts, weights)], eps=1e-3)
            built += 1
        except ValueError:
            refused += 1
    assert built > 0 and refused > 0
