from os import PathLike
from typing import Any, Callable, Literal, Optional, Sequence, Union

import numpy as np
import numpy.typing as npt

_Faces = Union[npt.NDArray[np.integer], Sequence[Sequence[int]]]
_Progress = Optional[Union[Callable[[str, float], Any], Callable[[str, float, Optional[float]], Any]]]
_Path = Union[str, PathLike]

class Primitive:
    kind: str
    params: dict
    transform: npt.NDArray[np.float64]
    volume: float
    def to_mesh(self, detail: int = 16) -> tuple[npt.NDArray[np.float64], list[list[int]]]: ...

class Level:
    target: Optional[int]
    primitives: list[Primitive]
    counts: dict[str, int]
    bytes: int
    distance: Optional[dict]
    measured_to: Optional[Literal["solid", "mesh"]]
    def __len__(self) -> int: ...

class Result:
    levels: list[Level]
    stats: dict
    input: dict
    def to_json(self, level: int = 0) -> str: ...
    def export(self, path: _Path, level: int = 0) -> list[str]: ...

def load(path: _Path) -> tuple[npt.NDArray[np.float64], Union[npt.NDArray[np.uint32], list[list[int]]]]: ...
def decompose(vertices: npt.ArrayLike, faces: _Faces, progress: _Progress = None, **settings: Any) -> Result: ...
def decompose_file(path: _Path, progress: _Progress = None, **settings: Any) -> Result: ...
def as_hulls(
    vertices: npt.ArrayLike, faces: _Faces, progress: _Progress = None, **settings: Any
) -> list[list[npt.NDArray[Any]]]: ...
