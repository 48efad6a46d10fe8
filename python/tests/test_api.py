"""Shapes, dtypes, layouts and errors of `revdist.distance`, and the certified mesh."""

import numpy as np
import pytest

import revdist
from conftest import random_poses


def quat_to_matrix(p):
    """Homogeneous matrices of poses [t, q] by the textbook formula (independent of the
    package's conversion)."""
    t, q = p[:, :3], p[:, 3:] / np.linalg.norm(p[:, 3:], axis=1)[:, None]
    w, x, y, z = q.T
    m = np.zeros((len(p), 4, 4))
    m[:, 0, :3] = np.stack([1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)], 1)
    m[:, 1, :3] = np.stack([2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)], 1)
    m[:, 2, :3] = np.stack([2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)], 1)
    m[:, :3, 3] = t
    m[:, 3, 3] = 1.0
    return m


def assert_same_certificate(r, s):
    """Two answers for (almost) the same pose: their certified intervals meet."""
    assert np.all(np.maximum(r.lower, s.lower) <= np.minimum(r.upper, s.upper) + 1e-12)


def test_result_arrays(pawn_cup):
    a, b = pawn_cup
    poses = random_poses(np.random.default_rng(1), 40, 1.2)
    r = revdist.distance(a, b, poses)
    assert len(r) == 40
    for key in ("value", "lower", "upper"):
        assert getattr(r, key).shape == (40,) and getattr(r, key).dtype == np.float64
    assert r.point_a.shape == r.point_b.shape == (40, 3)
    assert r.overlap.dtype == bool and r.width_limit.shape == (40,)
    assert set(r.width_limit) <= set(revdist.WIDTH_LIMITS)
    assert np.all(r.lower <= r.value) and np.all(r.value <= r.upper)
    assert np.all(r.upper - r.lower <= 2e-3 + 1e-12)  # default tolerance eps_a + eps_b
    assert np.all(r.value[r.overlap] == 0) and r.overlap.any() and (~r.overlap).any()
    # The witnesses realise the distance (up to rounding).
    sep = ~r.overlap
    gap = np.linalg.norm(r.point_a[sep] - r.point_b[sep], axis=1)
    assert np.allclose(gap, r.value[sep], rtol=0, atol=1e-9)


def test_pose_layouts_agree(pawn_cup):
    a, b = pawn_cup
    poses = random_poses(np.random.default_rng(2), 30, 1.0)
    r = revdist.distance(a, b, poses)
    # Strided and Fortran-ordered views are read in place and give the same bits.
    wide = np.zeros((30, 9))
    wide[:, 1:8] = poses
    for view in (wide[:, 1:8], np.asfortranarray(poses), poses.tolist()):
        s = revdist.distance(a, b, view)
        assert np.array_equal(s.value, r.value) and np.array_equal(s.point_b, r.point_b)
    # Homogeneous matrices of the same poses.
    s = revdist.distance(a, b, quat_to_matrix(poses))
    assert_same_certificate(r, s)
    assert np.allclose(s.value, r.value, atol=1e-3)
    # One pose, (7,) or (4, 4): scalars and (3,) points.
    one = revdist.distance(a, b, poses[3])
    assert isinstance(one.value, float) and one.value == r.value[3]
    assert one.point_a.shape == (3,) and isinstance(one.overlap, bool)
    one_m = revdist.distance(a, b, quat_to_matrix(poses[3:4])[0])
    assert one_m.lower <= one.upper and one.lower <= one_m.upper
    # Integer poses convert exactly; threads do not change the answers.
    ints = np.array([[2, 0, 0, 1, 0, 0, 0]])
    assert revdist.distance(a, b, ints).value[0] == revdist.distance(a, b, ints.astype(float)).value[0]
    assert np.array_equal(revdist.distance(a, b, poses, threads=1).value, r.value)


def test_pose_a_moves_the_pair_rigidly(pawn_cup):
    """A at M and B at M p is the configuration of A at I and B at p moved by M."""
    a, b = pawn_cup
    rng = np.random.default_rng(3)
    poses = random_poses(rng, 25, 1.0)
    m = quat_to_matrix(random_poses(rng, 1, 2.0))[0]
    r = revdist.distance(a, b, poses)
    moved = m @ quat_to_matrix(poses)
    s = revdist.distance(a, b, moved, pose_a=m)
    assert_same_certificate(r, s)
    back = (s.point_a - m[:3, 3]) @ m[:3, :3]
    assert np.allclose(back[~r.overlap], r.point_a[~r.overlap], atol=1e-2)
    # One pose_a per pose.
    per = revdist.distance(a, b, moved, pose_a=np.repeat(m[None], 25, axis=0))
    assert np.array_equal(per.value, s.value)


@pytest.mark.parametrize(
    "poses, message",
    [
        (np.zeros((3, 6)), "poses must have shape (N, 7)"),
        (np.zeros((2, 3, 3)), "got shape (2, 3, 3)"),
        (np.zeros(5), "got shape (5,)"),
        (np.array([[0, 0, 0, 1, 0, 0, 0.5]]), "poses[0]: rotation [1.0, 0.0, 0.0, 0.5] is not a unit quaternion [w, x, y, z] (norm 1.118033988749895, more than 1e-3 from 1); normalised it is [0.8944271909999159, 0.0, 0.0, 0.4472135954999579]"),
        (np.array([[np.nan, 0, 0, 1, 0, 0, 0]]), "poses[0]: translation.x is NaN, not a finite number"),
        (np.array([[0, 0, 0, np.nan, 0, 0, 0]]), "poses[0]: rotation [NaN, 0.0, 0.0, 0.0] is not a unit quaternion"),
        (np.array([[0, 0, 0, 1, 0, 0, 0]], dtype=complex), "must be an array of real numbers (float64), got dtype complex128"),
        (np.array([["a"] * 7]), "got dtype <U1"),
        (np.diag([1.0, 1.0, 1.0, 2.0]), "poses: the last row of a homogeneous matrix must be [0, 0, 0, 1]"),
        (np.diag([1.0, 1.0, -1.0, 1.0]), "poses: the upper-left 3x3 block is not a rotation matrix"),
        (np.array([[0, 0, 0, 1, 0, 0, 0], [0, 0, 0, 0.9, 0, 0, 0]]), "poses[1]: rotation"),
    ],
)
def test_bad_poses_raise_value_error(pawn_cup, poses, message):
    a, b = pawn_cup
    with pytest.raises(ValueError) as e:
        revdist.distance(a, b, poses)
    assert message in str(e.value)


def test_bad_options_raise_value_error(pawn_cup):
    a, b = pawn_cup
    p = np.array([1.0, 0, 0, 1, 0, 0, 0])
    for kwargs, message in [
        ({"threads": 0}, "threads must be at least 1"),
        ({"tolerance": float("nan")}, "tolerance must be a non-negative number, got NaN"),
        ({"max_time_ms": 0.0}, "max_time_ms must be a positive number, got 0"),
        ({"pose_a": np.zeros((2, 7)) + [0, 0, 0, 1, 0, 0, 0]}, "pose_a holds 2 poses and poses 1"),
    ]:
        with pytest.raises(ValueError) as e:
            revdist.distance(a, b, p, **kwargs)
        assert message in str(e.value)
    with pytest.raises(ValueError, match="eps must be a positive number, got 0"):
        revdist.Solid.model("pawn", eps=0.0)
    with pytest.raises(ValueError, match="which rounding cannot certify"):
        revdist.Solid.model("pawn", eps=1e-15)
    with pytest.raises(TypeError):
        revdist.distance(a, "cup", p)


def test_a_budget_answers_with_the_bounds_reached(pawn_cup):
    a, b = pawn_cup
    poses = random_poses(np.random.default_rng(4), 20, 1.0)
    full = revdist.distance(a, b, poses, tolerance=0.0)
    cut = revdist.distance(a, b, poses, tolerance=0.0, max_node_pairs=2)
    assert cut.budget_exhausted.any()
    assert set(cut.width_limit[cut.budget_exhausted]) <= {"budget", "met"}
    assert np.all(cut.lower <= full.upper + 1e-12) and np.all(full.lower <= cut.upper + 1e-12)


def test_tessellation_is_a_closed_certified_mesh():
    """The sphere model (centre (0, 0, 0.75), radius 0.75: its vertex extent) as a mesh:
    closed and oriented (every edge twice, once each way), genus 0, every vertex within eps
    of the sphere and the faces' centroids too."""
    s = revdist.Solid.model("sphere", eps=1e-3)
    eps = 1e-3
    v, f = s.tessellate(eps)
    assert v.dtype == np.float64 and f.dtype == np.int64 and v.shape[1] == f.shape[1] == 3
    assert f.min() >= 0 and f.max() < len(v)
    edges = np.concatenate([f[:, [0, 1]], f[:, [1, 2]], f[:, [2, 0]]])
    directed = {tuple(e) for e in edges.tolist()}
    assert len(directed) == len(edges) and all((j, i) in directed for i, j in directed)
    assert len(v) - len(edges) // 2 + len(f) == 2
    centre = np.array([0.0, 0.0, 0.75])
    for pts in (v, v[f].mean(axis=1)):
        assert np.all(np.abs(np.linalg.norm(pts - centre, axis=1) - 0.75) <= eps)
    with pytest.raises(ValueError, match="eps must be positive and finite"):
        s.tessellate(-1.0)


def test_the_stubs_cover_the_public_names():
    """Every public name has a type stub, and every stubbed method exists."""
    import ast
    import pathlib

    stub = ast.parse((pathlib.Path(revdist.__file__).parent / "__init__.pyi").read_text())
    names = {n.name for n in stub.body if isinstance(n, (ast.ClassDef, ast.FunctionDef))}
    names |= {t.id for n in stub.body if isinstance(n, ast.AnnAssign) for t in [n.target]}
    assert set(revdist.__all__) <= names
    for cls in (n for n in stub.body if isinstance(n, ast.ClassDef)):
        for f in cls.body:
            if isinstance(f, ast.FunctionDef) and not f.name.startswith("__"):
                assert hasattr(getattr(revdist, cls.name), f.name), (cls.name, f.name)
