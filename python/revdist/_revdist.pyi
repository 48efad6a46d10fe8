"""Type stubs of the compiled extension `revdist._revdist` (use the `revdist` package)."""

from os import PathLike
from typing import Any, Optional, Union

import numpy as np
import numpy.typing as npt

DEFAULT_EPS: float
WIDTH_LIMITS: list[str]

class Solid:
    @staticmethod
    def model(name: str, eps: float = ...) -> Solid: ...
    @staticmethod
    def from_file(path: Union[str, PathLike[str]], eps: float = ...) -> Solid: ...
    @staticmethod
    def load(spec: str, eps: float = ...) -> Solid: ...
    @property
    def spec(self) -> str: ...
    @property
    def eps(self) -> float: ...
    @property
    def nodes(self) -> int: ...
    def tessellate(
        self, eps: float, on_surface: bool = False
    ) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.int64]]: ...

class Pair:
    def __init__(self, a: Solid, b: Solid) -> None: ...
    def distance(
        self,
        poses: npt.NDArray[np.float64],
        *,
        pose_a: Optional[npt.NDArray[np.float64]] = None,
        tolerance: Optional[float] = None,
        max_time_ms: Optional[float] = None,
        max_node_pairs: Optional[int] = None,
        refine: bool = False,
        threads: Optional[int] = None,
        warm: bool = True,
    ) -> dict[str, Any]: ...
    def reset(self) -> None: ...

def models() -> list[str]: ...

TOI_OUTCOMES: list[str]

def time_of_impact(
    a: Solid,
    b: Solid,
    pose_b_start: npt.NDArray[np.float64],
    pose_b_end: npt.NDArray[np.float64],
    pose_a_start: Optional[npt.NDArray[np.float64]] = None,
    pose_a_end: Optional[npt.NDArray[np.float64]] = None,
    *,
    eps: Optional[float] = None,
    contact_distance: float = 0.0,
    threads: Optional[int] = None,
) -> dict[str, Any]: ...
