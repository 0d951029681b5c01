"""Type stub of the extension module lanecast._lanecast (python/src/), checked against the
built module by mypy's stubtest in python/ci.sh."""

import os
import pathlib
from collections.abc import Iterable
from typing import Any, Literal, SupportsIndex, Union, final

import numpy as np
import numpy.typing as npt

_Path = Union[str, bytes, "os.PathLike[str]", "os.PathLike[bytes]"]
_Vec3 = Union[npt.ArrayLike, tuple[float, float, float]]
_Precision = Literal["auto", "f32", "f64"]
_Int = SupportsIndex

__all__ = ["Camera", "INTRINSICS_TOL", "MAX_SIDE", "MAX_THREADS", "Render", "Scene",
           "__version__", "shade"]

__version__: str
INTRINSICS_TOL: float
MAX_SIDE: int
MAX_THREADS: int

@final
class Camera:
    def __new__(cls, eye: _Vec3, look: _Vec3, up: _Vec3 | None = None,
                fov: float = 60.0) -> Camera: ...
    @staticmethod
    def from_intrinsics(K: npt.ArrayLike, extrinsic: npt.ArrayLike, width: _Int,
                        height: _Int) -> Camera | list[Camera]: ...
    @property
    def eye(self) -> list[float]: ...
    @property
    def look(self) -> list[float]: ...
    @property
    def up(self) -> list[float]: ...
    @property
    def fov(self) -> float: ...
    @property
    def size(self) -> tuple[int, int] | None: ...
    def rays(self, width: _Int | None = None,
             height: _Int | None = None) -> npt.NDArray[np.float64]: ...
    def __eq__(self, value: object, /) -> bool: ...
    def _state(self) -> tuple[list[float], list[float], list[float], float,
                              tuple[int, int] | None]: ...
    @staticmethod
    def _from_state(state: tuple[Any, ...]) -> Camera: ...

@final
class Render:
    @property
    def ids(self) -> npt.NDArray[np.int32]: ...
    @property
    def depth(self) -> npt.NDArray[np.float32]: ...
    @property
    def zdepth(self) -> npt.NDArray[np.float32]: ...
    @property
    def normals(self) -> npt.NDArray[np.float32]: ...
    def image(self, color_mode: Literal["random", "ordered"] = "random",
              variation: Literal["linear", "log"] = "linear",
              seed: _Int = 0) -> npt.NDArray[np.uint8]: ...

@final
class Scene:
    @staticmethod
    def load(path: _Path) -> Scene: ...
    @staticmethod
    def from_arrays(vertices: npt.ArrayLike | None = None,
                    triangles: npt.ArrayLike | None = None,
                    quads: npt.ArrayLike | None = None,
                    spheres: npt.ArrayLike | None = None,
                    camera: Camera | None = None, name: str = "<arrays>") -> Scene: ...
    @property
    def source(self) -> pathlib.Path: ...
    @property
    def warnings(self) -> list[str]: ...
    @property
    def camera(self) -> Camera: ...
    @property
    def counts(self) -> tuple[int, int, int]: ...
    def __len__(self) -> int: ...
    def render(self, camera: Camera | None = None, width: _Int | None = None,
               height: _Int | None = None, precision: _Precision = "auto",
               threads: _Int | None = None, zdepth: bool = False,
               normals: bool = False) -> Render: ...
    def render_views(self, cameras: Iterable[Camera], width: _Int | None = None,
                     height: _Int | None = None, precision: _Precision = "auto",
                     threads: _Int | None = None, zdepth: bool = False,
                     normals: bool = False) -> Render: ...
    def _state(self) -> tuple[Any, ...]: ...
    @staticmethod
    def _from_state(state: tuple[Any, ...]) -> Scene: ...

def shade(ids: npt.ArrayLike, depth: npt.ArrayLike,
          color_mode: Literal["random", "ordered"] = "random",
          variation: Literal["linear", "log"] = "linear",
          seed: _Int = 0) -> npt.NDArray[np.uint8]: ...
