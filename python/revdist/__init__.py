"""Certified minimum distances between solids of revolution, for numpy arrays of poses.

revdist (Son, Yoon, Kim, Elber 2020: biarc trees of a planar profile, revolved into fat
toroidal patches) answers each query with a certified interval ``lower <= true distance <=
upper`` and two witness points. This package calls the Rust core directly: the GIL is
released for the whole batch, poses are spread over the cores, and each answer is the same
bits as ``revdist distance --batch`` gives for the same query.

Poses: a point ``x`` of a solid's own frame (axis of revolution = z) is at ``R x + t``.
Give them as ``(N, 7)`` rows ``[tx, ty, tz, qw, qx, qy, qz]`` (unit quaternion, w first;
norms within 1e-3 of 1 are normalised and the answer is certified for the normalised pose),
``(N, 4, 4)`` homogeneous matrices, or one pose as ``(7,)`` or ``(4, 4)``.

>>> import numpy as np, revdist
>>> a = revdist.Solid.model("pawn", eps=1e-4)
>>> b = revdist.Solid.model("cup", eps=1e-4)
>>> r = revdist.distance(a, b, np.array([[1.2, 0.0, 0.3, 1.0, 0.0, 0.0, 0.0]]))
>>> bool(r.lower[0] <= r.value[0] <= r.upper[0])
True
"""

from __future__ import annotations

import numpy as np

from . import _revdist
from ._revdist import DEFAULT_EPS, WIDTH_LIMITS, Solid, models
from ._toi import TimeOfImpactResult, time_of_impact

__all__ = [
    "DEFAULT_EPS",
    "WIDTH_LIMITS",
    "DistanceResult",
    "Pair",
    "Solid",
    "TimeOfImpactResult",
    "distance",
    "models",
    "time_of_impact",
]

_WIDTH_NAMES = np.array(WIDTH_LIMITS)

# Largest integer that float64 holds exactly: integer poses beyond it would be rounded.
_EXACT_INT = 2**53


def _as_float64(name, array):
    """``array`` as float64 without a copy when it already is; real dtypes that convert
    exactly (float16/32, integers up to 2**53) are converted, others raise ValueError."""
    arr = np.asarray(array)
    if arr.dtype == np.float64:
        return arr
    kind = arr.dtype.kind
    if kind == "f":
        return arr.astype(np.float64)
    if kind in "iu":
        if arr.size and np.abs(arr.astype(np.float64)).max() > _EXACT_INT:
            raise ValueError(f"{name}: integers beyond 2**53 do not convert exactly to float64")
        return arr.astype(np.float64)
    raise ValueError(f"{name} must be an array of real numbers (float64), got dtype {arr.dtype}")


class DistanceResult:
    """Certified distances for a batch of poses (numpy arrays, one entry per pose).

    value, lower, upper : float64 (N,)
        The best estimate and the certified interval ``lower <= true distance <= upper``.
    point_a, point_b : float64 (N, 3)
        Witness points on A and B in the world frame (A's frame when A is at the identity).
    gradient_translation, gradient_rotation : float64 (N, 3)
        The distance's derivative with respect to B's translation, and with respect to a
        rotation vector of B about its frame origin: ``n`` and ``(point_b - origin_b) x n``
        with ``n`` the unit vector from point_a to point_b. NaN unless the solids are
        certified apart; the gradient where the closest pair is unique, else a
        supergradient (the command line's ``gradient``, ``docs/cli.md``).
    overlap : bool (N,)
        The solids certainly overlap or nest (then value = lower = upper = 0).
    width_limit : str (N,)
        ``"met"`` when ``upper - lower`` is within the requested width, else what held it
        back: ``"budget"``, ``"rounding"`` (the slack at this configuration's scale) or
        ``"leaves"`` (the trees' own accuracy: build them with a smaller eps).
    budget_exhausted, closed_form : bool (N,)
        The anytime budget ran out; answered in closed form (two balls or solid tori).
    node_pairs, leaf_bounds, leaf_tests, subdivided_pairs : uint64 (N,)
        What each query did (the command line's JSON counters).

    With ``signed=True`` (else these are None):

    signed_lower, signed_upper : float64 (N,)
        Certified interval of the signed distance: the distance when the solids are apart,
        minus the penetration depth when they overlap (``[-pd_upper, -pd_lower]``), and
        ``[-pd_upper, upper]`` when they touch within the trees' accuracy.
    pd_lower, pd_upper : float64 (N,)
        Certified interval ``pd_lower <= PD <= pd_upper`` of the translational penetration
        depth ``PD = min |t|`` over translations ``t`` of B that leave the interiors
        disjoint. Exactly ``0.0`` (both) where the solids are certified apart (their depth
        is 0); ``pd_lower`` is 0 where no common interior point was certified (touching).
    pd_direction : float64 (N, 3)
        Unit translation of B achieving ``pd_upper`` (B moved by more than ``pd_upper``
        along it is apart from A), world frame; zeros where the solids are certified apart.

    With ``signed=True`` the gradient arrays hold the *signed* distance's gradient: the
    distance's when apart; where the solids overlap and ``pd_upper - pd_lower <= max(2
    (eps_a + eps_b), 5 % of pd_upper)``, that of ``-PD`` (``pd_direction`` in translation,
    ``(contact_b - origin_b) x pd_direction`` in rotation; a one-sided derivative where the
    minimal separating translation is not unique); NaN otherwise (``docs/cli.md``,
    ``--signed``).

    A result of a single pose ``(7,)`` or ``(4, 4)`` holds scalars and ``(3,)`` points.
    """

    __slots__ = (
        "value",
        "lower",
        "upper",
        "point_a",
        "point_b",
        "gradient_translation",
        "gradient_rotation",
        "overlap",
        "width_limit",
        "budget_exhausted",
        "closed_form",
        "node_pairs",
        "leaf_bounds",
        "leaf_tests",
        "subdivided_pairs",
        "signed_lower",
        "signed_upper",
        "pd_lower",
        "pd_upper",
        "pd_direction",
    )

    def __init__(self, arrays):
        single = arrays.pop("single")
        arrays["width_limit"] = _WIDTH_NAMES[arrays.pop("width_limit_code")]
        for key in self.__slots__:
            value = arrays.get(key)
            if value is None:
                # The signed fields of an unsigned call.
                object.__setattr__(self, key, None)
                continue
            if single:
                value = value[0]
                value = value.item() if np.ndim(value) == 0 else value
            object.__setattr__(self, key, value)

    def __len__(self):
        return 1 if np.ndim(self.value) == 0 else len(self.value)

    def __repr__(self):
        if np.ndim(self.value) == 0:
            return (
                f"DistanceResult(value={self.value!r}, lower={self.lower!r}, "
                f"upper={self.upper!r}, overlap={self.overlap!r}, width_limit={self.width_limit!r})"
            )
        return f"DistanceResult(N={len(self)}, value={self.value!r})"


def _pose_arg(name, pose):
    return None if pose is None else _as_float64(name, pose)


def distance(
    a,
    b,
    poses,
    *,
    pose_a=None,
    tolerance=None,
    max_time_ms=None,
    max_node_pairs=None,
    refine=False,
    threads=None,
    signed=False,
):
    """Certified distances between solid ``a`` and solid ``b`` at each of ``poses``.

    Parameters
    ----------
    a, b : Solid
    poses : array_like
        B's poses: ``(N, 7)`` rows ``[tx, ty, tz, qw, qx, qy, qz]``, ``(N, 4, 4)`` matrices,
        or one pose ``(7,)`` / ``(4, 4)``. float64 arrays are read in place (any strides).
    pose_a : array_like, optional
        A's pose (one, or one per pose of B); default the identity, as in the command line.
    tolerance : float, optional
        Width of the certified interval ``upper - lower``; default the trees' accuracy
        ``eps_a + eps_b``; 0 runs until nothing can be narrowed.
    max_time_ms : float, optional
        Anytime budget per query: a query that runs out answers with the bounds reached,
        flagged ``budget_exhausted`` (its answer then depends on the machine's speed).
    max_node_pairs : int, optional
        Anytime budget per query in node pairs (deterministic).
    refine : bool
        Refine the witness points on the exact NURBS surfaces.
    threads : int, optional
        Worker threads (default: every core; concurrent calls share them). ``threads=1``
        runs on the calling thread, so that several Python threads run side by side;
        calls with the same ``threads=k > 1`` share one pool of k threads. Answers do not
        depend on it.
    signed : bool
        Also the signed distance and the certified penetration depth of overlapping solids
        (``signed_lower``, ``signed_upper``, ``pd_lower``, ``pd_upper``, ``pd_direction``;
        see :class:`DistanceResult`), the command line's ``distance --signed``, the same
        bits. Costs one distance query where the solids are certified apart, and a search
        (a few more distance queries) where they are not.

    Returns
    -------
    DistanceResult

    Raises
    ------
    ValueError
        Bad shapes or dtypes, non-unit quaternions, non-rotation matrices, NaN, a pose
        outside the representable range, bad options; the message is the command line's,
        prefixed with where (``poses[3]: rotation [...] is not a unit quaternion ...``).
    """
    poses = _as_float64("poses", poses)
    pose_a = _pose_arg("pose_a", pose_a)
    # A fresh pair, cold queries: the extension's one entry point, which Pair uses warm.
    arrays = _revdist.Pair(a, b).distance(
        poses,
        pose_a=pose_a,
        tolerance=tolerance,
        max_time_ms=max_time_ms,
        max_node_pairs=max_node_pairs,
        refine=refine,
        threads=threads,
        warm=False,
        signed=signed,
    )
    return DistanceResult(arrays)


class Pair:
    """A prepared pair of solids for a motion: each query warm-starts from the previous
    one's closest leaf pair, which saves time when consecutive poses are close. Answers are
    certified like cold ones (their intervals hold the true distance) but may differ from
    them in the last bits. Queries of one Pair run in order, one call at a time; the GIL is
    released while they run. A Pair pickles (for multiprocessing, Dask, Ray, joblib) by its
    two solids; the unpickled Pair starts cold.

    >>> pair = Pair(a, b)                 # doctest: +SKIP
    >>> r = pair.distance(poses)          # doctest: +SKIP
    """

    __slots__ = ("_pair", "a", "b")

    def __init__(self, a, b):
        self._pair = _revdist.Pair(a, b)
        self.a = a
        self.b = b

    def distance(
        self,
        poses,
        *,
        pose_a=None,
        tolerance=None,
        max_time_ms=None,
        max_node_pairs=None,
        refine=False,
        signed=False,
    ):
        """Distances at ``poses`` in order (arguments as :func:`distance`, without
        ``threads``: a motion is sequential). Signed queries (``signed=True``) run cold,
        neither using nor changing the warm start."""
        arrays = self._pair.distance(
            _as_float64("poses", poses),
            pose_a=_pose_arg("pose_a", pose_a),
            tolerance=tolerance,
            max_time_ms=max_time_ms,
            max_node_pairs=max_node_pairs,
            refine=refine,
            signed=signed,
        )
        return DistanceResult(arrays)

    def reset(self):
        """Forget the warm start: the next query is cold."""
        self._pair.reset()

    def __reduce__(self):
        # Pickled by its two solids (each by its recipe); the warm start stays behind, so
        # an unpickled Pair starts cold: its first answer is a cold query's bits.
        return (Pair, (self.a, self.b))

    def __repr__(self):
        return f"revdist.Pair({self.a!r}, {self.b!r})"
