"""``revdist.time_of_impact``: certified time of impact for numpy arrays of motions."""

from __future__ import annotations

import numpy as np

from . import _revdist

_OUTCOMES = np.array(_revdist.TOI_OUTCOMES)


def _poses(name, array):
    if array is None:
        return None
    arr = np.asarray(array)
    if arr.dtype.kind not in "fiu":
        raise ValueError(f"{name} must be an array of real numbers (float64), got dtype {arr.dtype}")
    return arr.astype(np.float64, copy=False)


class TimeOfImpactResult:
    """Certified times of impact for N motions (numpy arrays, one entry per motion).

    outcome : str (N,)
        ``"contact"`` (apart on ``[0, t_lower)``, distance <= contact_distance at
        ``t_upper``), ``"apart"`` (distance > contact_distance on all of ``[0, 1]``) or
        ``"undecided"`` (apart before ``t_lower``, no contact certified after it).
    t_lower, t_upper : float64 (N,)
        The certified interval of the first contact; ``t_upper`` is NaN unless a contact.
    point_a, point_b : float64 (N, 3)
        Witnesses of the contact at ``t_upper`` (world frame): one point inside both solids
        (equal points), or a point of each within contact_distance; NaN unless a contact.
    upper_at_upper : float64 (N,)
        Certified upper bound of the distance at ``t_upper``.
    queries, certificates : int64 (N,)
        Distance queries and carried contact certificates the search spent.
    speed_bound : float64 (N,)
        The proved bound on how fast the distance can change, at t = 0.
    """

    def __init__(self, arrays):
        self.outcome = _OUTCOMES[arrays["outcome_code"]]
        self.t_lower = arrays["t_lower"]
        self.t_upper = arrays["t_upper"]
        self.upper_at_upper = arrays["upper_at_upper"]
        self.point_a = arrays["point_a"]
        self.point_b = arrays["point_b"]
        self.queries = arrays["queries"]
        self.certificates = arrays["certificates"]
        self.speed_bound = arrays["speed_bound"]

    def __len__(self):
        return len(self.t_lower)

    def __repr__(self):
        return f"TimeOfImpactResult({len(self)} motions)"


def time_of_impact(
    a,
    b,
    pose_b_start,
    pose_b_end,
    pose_a_start=None,
    pose_a_end=None,
    eps=None,
    contact_distance=0.0,
    threads=None,
):
    """Certified first contact of ``a`` and ``b`` along N motions over ``t in [0, 1]``.

    B moves from ``pose_b_start`` to ``pose_b_end`` and A from ``pose_a_start`` (default
    the identity) to ``pose_a_end`` (default its start): constant linear and angular
    velocity (the shortest arc), as ``revdist toi``. Poses as for ``revdist.distance``:
    ``(N, 7)`` rows or ``(N, 4, 4)`` matrices, or one pose (``(7,)``, ``(4, 4)``) for every
    motion. ``eps``: rebuild both solids' trees at this bound (default: their own).
    ``threads``: worker threads (default every core). The GIL is released while the
    searches run. Returns a :class:`TimeOfImpactResult`.
    """
    return TimeOfImpactResult(
        _revdist.time_of_impact(
            a,
            b,
            _poses("pose_b_start", pose_b_start),
            _poses("pose_b_end", pose_b_end),
            _poses("pose_a_start", pose_a_start),
            _poses("pose_a_end", pose_a_end),
            eps=eps,
            contact_distance=float(contact_distance),
            threads=threads,
        )
    )
