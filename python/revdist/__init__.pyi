"""Type stubs of the `revdist` package: certified distances between solids of revolution."""

from os import PathLike
from typing import Optional, Union

import numpy as np
import numpy.typing as npt

DEFAULT_EPS: float
"""Default bound of the biarc trees (1e-4, the command line's)."""
WIDTH_LIMITS: list[str]
"""The values of `DistanceResult.width_limit`: met, budget, rounding, leaves."""

PoseArray = npt.ArrayLike
"""(N, 7) rows [tx, ty, tz, qw, qx, qy, qz], (N, 4, 4) matrices, or one (7,) / (4, 4) pose."""

class Solid:
    """A solid of revolution held as a biarc tree of two-sided Hausdorff bound eps."""

    @staticmethod
    def model(name: str, eps: float = ...) -> Solid:
        """A built-in model (see models(); "morph@0.25" too). ValueError for unknown names."""
    @staticmethod
    def from_file(path: Union[str, PathLike[str]], eps: float = ...) -> Solid:
        """A TOML profile file. FileNotFoundError when missing, ValueError when invalid."""
    @staticmethod
    def load(spec: str, eps: float = ...) -> Solid:
        """A built-in name, else a file path, resolved as the command line does."""
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
) -> DistanceResult:
    """Certified distances between a (at pose_a, default identity) and b at each pose;
    the GIL is released and the poses are spread over the cores."""

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
    ) -> DistanceResult: ...
    def reset(self) -> None: ...

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
