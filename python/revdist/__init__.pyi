"""Type stubs of the `revdist` package: certified distances between solids of revolution."""

from os import PathLike
from typing import Any, Optional, Sequence, TypedDict, Union

import numpy as np
import numpy.typing as npt

DEFAULT_EPS: float
"""Default bound of the biarc trees (1e-4, the command line's)."""
WIDTH_LIMITS: list[str]
"""The values of `DistanceResult.width_limit`: met, budget, rounding, leaves."""

PoseArray = npt.ArrayLike
"""(N, 7) rows [tx, ty, tz, qw, qx, qy, qz], (N, 4, 4) matrices, or one (7,) / (4, 4) pose."""

class NurbsPiece(TypedDict):
    """One NURBS piece of a profile: knots (k,), points (n, 2) [rho, z], weights (n,) or None."""

    degree: int
    knots: npt.NDArray[np.float64]
    points: npt.NDArray[np.float64]
    weights: Optional[npt.NDArray[np.float64]]

class Solid:
    """A solid of revolution held as a biarc tree of two-sided Hausdorff bound eps.
    Immutable; pickles by its recipe (built-in name or profile pieces) and is rebuilt on
    load to the same bits."""

    @staticmethod
    def model(name: str, eps: float = ...) -> Solid:
        """A built-in model (see models(); "morph@0.25" too). ValueError for unknown names."""
    @staticmethod
    def from_file(path: Union[str, PathLike[str]], eps: float = ...) -> Solid:
        """A TOML profile file. FileNotFoundError when missing, ValueError when invalid."""
    @staticmethod
    def load(spec: str, eps: float = ...) -> Solid:
        """A built-in name, else a file path, resolved as the command line does."""
    @staticmethod
    def from_polyline(rz: npt.ArrayLike, eps: float = ..., name: str = "polyline") -> Solid:
        """A polyline (n, 2) of [rho, z] points, open with both ends on the axis or closed
        (last point = first); one line piece per segment, corners allowed. ValueError names
        the problem (self-intersection, rho < 0, NaN, shape)."""
    @staticmethod
    def from_nurbs(
        pieces: Sequence[Union[NurbsPiece, Sequence[Any]]], eps: float = ..., name: str = "nurbs"
    ) -> Solid:
        """NURBS pieces joined end to start: dicts {degree, knots, points, weights} or
        sequences (degree, knots, points[, weights]); checked as a profile file is."""
    def profile(self) -> list[NurbsPiece]:
        """The exact profile's pieces as arrays (what from_nurbs takes back)."""
    @property
    def kind(self) -> str:
        """"closed" (a loop in rho > 0) or "open" (both ends on the axis)."""
    @property
    def spec(self) -> str: ...
    @property
    def eps(self) -> float: ...
    @property
    def nodes(self) -> int: ...
    def tessellate(
        self, eps: float, on_surface: bool = False
    ) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.int64]]:
        """(V, F): a closed mesh within a certified Hausdorff distance eps of the surface."""

class DistanceResult:
    """Certified answers, one entry per pose (scalars for a single pose)."""

    value: npt.NDArray[np.float64]
    lower: npt.NDArray[np.float64]
    upper: npt.NDArray[np.float64]
    point_a: npt.NDArray[np.float64]
    point_b: npt.NDArray[np.float64]
    gradient_translation: npt.NDArray[np.float64]
    gradient_rotation: npt.NDArray[np.float64]
    overlap: npt.NDArray[np.bool_]
    width_limit: npt.NDArray[np.str_]
    budget_exhausted: npt.NDArray[np.bool_]
    closed_form: npt.NDArray[np.bool_]
    node_pairs: npt.NDArray[np.uint64]
    leaf_bounds: npt.NDArray[np.uint64]
    leaf_tests: npt.NDArray[np.uint64]
    subdivided_pairs: npt.NDArray[np.uint64]
    signed_lower: Optional[npt.NDArray[np.float64]]
    """signed=True: certified lower bound of the signed distance (-PD upper when overlapping)."""
    signed_upper: Optional[npt.NDArray[np.float64]]
    pd_lower: Optional[npt.NDArray[np.float64]]
    """signed=True: certified lower bound of the penetration depth; 0.0 where certified apart."""
    pd_upper: Optional[npt.NDArray[np.float64]]
    """signed=True: certified upper bound of the penetration depth; 0.0 where certified apart."""
    pd_direction: Optional[npt.NDArray[np.float64]]
    """signed=True: unit translation of B achieving pd_upper (N, 3); zeros where apart."""
    def __len__(self) -> int: ...

def distance(
    a: Solid,
    b: Solid,
    poses: PoseArray,
    *,
    pose_a: Optional[PoseArray] = None,
    tolerance: Optional[float] = None,
    max_time_ms: Optional[float] = None,
    max_node_pairs: Optional[int] = None,
    refine: bool = False,
    threads: Optional[int] = None,
    signed: bool = False,
) -> DistanceResult:
    """Certified distances between a (at pose_a, default identity) and b at each pose;
    the GIL is released and the poses are spread over the cores. signed=True adds the
    signed distance and the penetration depth's certified interval."""

class Pair:
    """A prepared pair for a motion: consecutive poses warm-start each other."""

    a: Solid
    b: Solid
    def __init__(self, a: Solid, b: Solid) -> None: ...
    def distance(
        self,
        poses: PoseArray,
        *,
        pose_a: Optional[PoseArray] = None,
        tolerance: Optional[float] = None,
        max_time_ms: Optional[float] = None,
        max_node_pairs: Optional[int] = None,
        refine: bool = False,
        signed: bool = False,
    ) -> DistanceResult: ...
    def reset(self) -> None: ...
    def __reduce__(self) -> tuple[Any, ...]: ...

def models() -> list[str]:
    """Names of the built-in models."""

class TimeOfImpactResult:
    """Certified first-contact intervals for N motions (numpy arrays, one entry per motion)."""

    outcome: npt.NDArray[np.str_]
    t_lower: npt.NDArray[np.float64]
    t_upper: npt.NDArray[np.float64]
    upper_at_upper: npt.NDArray[np.float64]
    point_a: npt.NDArray[np.float64]
    point_b: npt.NDArray[np.float64]
    queries: npt.NDArray[np.int64]
    certificates: npt.NDArray[np.int64]
    speed_bound: npt.NDArray[np.float64]
    def __len__(self) -> int: ...

def time_of_impact(
    a: Solid,
    b: Solid,
    pose_b_start: PoseArray,
    pose_b_end: PoseArray,
    pose_a_start: Optional[PoseArray] = None,
    pose_a_end: Optional[PoseArray] = None,
    eps: Optional[float] = None,
    contact_distance: float = 0.0,
    threads: Optional[int] = None,
) -> TimeOfImpactResult:
    """Certified first contact of a and b along N motions over t in [0, 1] (apart on
    [0, t_lower), distance <= contact_distance at t_upper); the GIL is released and the
    motions are spread over the cores."""
