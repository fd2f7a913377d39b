"""Type stubs of the compiled extension ``subdiv._subdiv`` (python/src/)."""

from __future__ import annotations

import os
from typing import Any, ClassVar, Dict, List, Optional, Tuple, Union

import numpy as np
import numpy.typing as npt

ArrayLike = npt.ArrayLike
PathLike = Union[str, "os.PathLike[str]"]
Csr = Tuple[npt.NDArray[np.float64], npt.NDArray[np.int32], npt.NDArray[np.int32], Tuple[int, int]]
LevelTuple = Tuple[
    np.ndarray,
    npt.NDArray[np.int32],
    npt.NDArray[np.int32],
    npt.NDArray[np.bool_],
    Optional[np.ndarray],
    Optional[npt.NDArray[np.int32]],
]

OSD_VERSION: str

class SubdivError(ValueError):
    """Base class of every error subdiv raises."""

class MeshError(SubdivError):
    """An invalid mesh."""

class ObjError(SubdivError):
    """A malformed OBJ file or text."""

class LevelError(SubdivError):
    """A refinement level refused."""

class OsdError(SubdivError):
    """The osd engine refused the input."""

class Mesh:
    """A validated polygon mesh with OpenSubdiv's tags."""

    def __init__(
        self,
        points: ArrayLike,
        face_counts: ArrayLike,
        face_indices: ArrayLike,
        *,
        creases: Optional[Tuple[ArrayLike, Union[ArrayLike, float]]] = None,
        corners: Optional[Tuple[ArrayLike, Union[ArrayLike, float]]] = None,
        holes: Optional[ArrayLike] = None,
        uvs: Optional[ArrayLike] = None,
        uv_indices: Optional[ArrayLike] = None,
        left_handed: bool = False,
    ) -> None: ...
    @property
    def points(self) -> npt.NDArray[np.float64]: ...
    @property
    def face_counts(self) -> npt.NDArray[np.int32]: ...
    @property
    def face_indices(self) -> npt.NDArray[np.int32]: ...
    @property
    def creases(self) -> Tuple[npt.NDArray[np.int32], npt.NDArray[np.float32]]: ...
    @property
    def corners(self) -> Tuple[npt.NDArray[np.int32], npt.NDArray[np.float32]]: ...
    @property
    def holes(self) -> npt.NDArray[np.int32]: ...
    @property
    def uvs(self) -> Optional[npt.NDArray[np.float64]]: ...
    @property
    def uv_indices(self) -> Optional[npt.NDArray[np.int32]]: ...
    @property
    def left_handed(self) -> bool: ...
    @property
    def vertex_count(self) -> int: ...
    @property
    def face_count(self) -> int: ...
    @property
    def warnings(self) -> List[str]: ...
    def validate_strict(self) -> None: ...
    def __eq__(self, other: object) -> bool: ...

class Options:
    """Subdivision options by the command line's names."""

    CHOICES: ClassVar[Dict[str, List[str]]]
    def __init__(
        self,
        scheme: str = "catmark",
        boundary: str = "edge-only",
        fvar: str = "all",
        creasing: str = "uniform",
        triangles: str = "catmark",
    ) -> None: ...
    @staticmethod
    def sdc_defaults() -> Options: ...
    @property
    def scheme(self) -> str: ...
    @property
    def boundary(self) -> str: ...
    @property
    def fvar(self) -> str: ...
    @property
    def creasing(self) -> str: ...
    @property
    def triangles(self) -> str: ...
    def replace(
        self,
        *,
        scheme: Optional[str] = None,
        boundary: Optional[str] = None,
        fvar: Optional[str] = None,
        creasing: Optional[str] = None,
        triangles: Optional[str] = None,
    ) -> Options: ...
    def __eq__(self, other: object) -> bool: ...
    def __hash__(self) -> int: ...

class Refiner:
    """Topology refined once, for many frames."""

    def __init__(
        self,
        mesh: Mesh,
        level: int = 2,
        options: Optional[Options] = None,
        engine: str = "native",
        faces_first: bool = False,
        full_topology: bool = True,
    ) -> None: ...
    @property
    def engine(self) -> str: ...
    @property
    def level(self) -> int: ...
    def topology(self, level: int) -> Tuple[npt.NDArray[np.int32], npt.NDArray[np.int32], npt.NDArray[np.bool_]]: ...
    def vertex_counts(self) -> List[int]: ...
    def interpolate(self, points: ArrayLike) -> List[np.ndarray]: ...
    def interpolate_last(self, points: ArrayLike) -> np.ndarray: ...
    def interpolate_face_varying(self, values: ArrayLike, channel: int = 0) -> List[np.ndarray]: ...
    def limit(self, points: ArrayLike) -> Tuple[np.ndarray, np.ndarray, np.ndarray]: ...
    def stencil_table(self) -> Csr: ...
    def limit_stencil_table(self) -> Tuple[Csr, Csr, Csr]: ...

def refine(
    mesh: Mesh,
    level: int = 2,
    options: Optional[Options] = None,
    engine: str = "native",
    precision: str = "f64",
    limit: bool = False,
    faces_first: bool = False,
) -> Tuple[List[LevelTuple], Optional[Tuple[np.ndarray, np.ndarray, np.ndarray, Optional[np.ndarray]]]]: ...
def compare(
    mesh: Mesh,
    level: int = 2,
    options: Optional[Options] = None,
    precision: str = "f64",
    limit: bool = False,
    faces_first: bool = False,
) -> Tuple[List[Dict[str, Any]], float, float]: ...
def evaluate(
    mesh: Mesh,
    faces: ArrayLike,
    uv: ArrayLike,
    options: Optional[Options] = None,
    isolation: int = 4,
    engine: str = "native",
    end_caps: str = "gregory-basis",
    single_crease: bool = False,
    inf_sharp: bool = False,
    double: bool = False,
    derivatives: bool = False,
    exact_limit: bool = False,
) -> Union[npt.NDArray[np.float64], Tuple[npt.NDArray[np.float64], npt.NDArray[np.float64], npt.NDArray[np.float64]]]: ...
def time_rust_refine(
    mesh: Mesh, level: int = 2, options: Optional[Options] = None, engine: str = "native", repeats: int = 1
) -> List[float]: ...
def read_obj(path: PathLike) -> Tuple[Mesh, Options, List[str]]: ...
def parse_obj(text: str, name: str = "<string>") -> Tuple[Mesh, Options, List[str]]: ...
def write_mesh_obj(path: PathLike, mesh: Mesh, precision: str = "f64") -> None: ...
def write_level_obj(
    path: PathLike,
    points: ArrayLike,
    face_counts: ArrayLike,
    face_indices: ArrayLike,
    holes: Optional[ArrayLike] = None,
    uvs: Optional[ArrayLike] = None,
    uv_indices: Optional[ArrayLike] = None,
    precision: str = "f64",
) -> None: ...
def corpus() -> List[Tuple[str, Mesh]]: ...
def builtin(name: str) -> Mesh: ...
def torus(nu: int, nv: int) -> Mesh: ...
def grid(nx: int, ny: int) -> Mesh: ...

