"""Type stubs of the compiled extension `revdist._revdist` (use the `revdist` package)."""

from os import PathLike
from typing import Any, Optional, Sequence, Union

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
    @staticmethod
    def from_polyline(rz: npt.ArrayLike, eps: float = ..., name: str = "polyline") -> Solid: ...
    @staticmethod
    def from_nurbs(pieces: Sequence[Any], eps: float = ..., name: str = "nurbs") -> Solid: ...
    def profile(self) -> list[dict[str, Any]]: ...
    @property
    def kind(self) -> str: ...
    def __reduce__(self) -> tuple[Any, ...]: ...
    def __copy__(self) -> Solid: ...
    def __deepcopy__(self, memo: dict[int, Any]) -> Solid: ...
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
        signed: bool = False,
    ) -> dict[str, Any]: ...
    def reset(self) -> None: ...

def models() -> list[str]: ...
def _solid_from_recipe(recipe: tuple[Any, ...]) -> Solid: ...

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
