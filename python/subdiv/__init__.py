"""subdiv: subdivision surfaces identical to Pixar's OpenSubdiv, numpy in, numpy out.

Two engines behind one API: ``"native"`` (pure Rust) and ``"osd"``
(OpenSubdiv 3.5 through a C++ shim). Both give the same arrays, bit for bit.

>>> import numpy as np, subdiv
>>> mesh = subdiv.Mesh(np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], float),
...                    face_counts=[4], face_indices=[0, 1, 2, 3])
>>> r = subdiv.refine(mesh, level=2)
>>> r.levels[-1].points.shape
(25, 3)

Classes: ``Mesh`` (validated base mesh), ``Options`` (scheme and OpenSubdiv's
options by the command line's names), ``Refiner`` (topology once, many frames;
limits; stencil tables). Functions: ``refine``, ``compare``, ``evaluate``
(the limit surface at ptex locations through a patch table), ``read_obj``,
``parse_obj``, ``write_obj``; ``subdiv.shapes`` generates meshes. Errors are
``SubdivError`` (a ``ValueError``) and its subclasses ``MeshError``,
``ObjError``, ``LevelError`` and ``OsdError``; wrong dtypes are ``TypeError``.
Refinement releases the GIL, so threads refine in parallel.
"""

from __future__ import annotations

import os
from dataclasses import dataclass, field
from typing import Any, List, NamedTuple, Optional, Tuple, Union

import numpy as np

from . import _subdiv
from . import shapes
from ._subdiv import (
    LevelError,
    Mesh,
    MeshError,
    ObjError,
    Options,
    OsdError,
    SubdivError,
)

__all__ = [
    "Comparison",
    "CsrMatrix",
    "Level",
    "LevelComparison",
    "LevelError",
    "Limit",
    "Mesh",
    "MeshError",
    "ObjError",
    "ObjFile",
    "OSD_VERSION",
    "Options",
    "OsdError",
    "Refinement",
    "Refiner",
    "SubdivError",
    "compare",
    "evaluate",
    "parse_obj",
    "read_obj",
    "refine",
    "shapes",
    "write_obj",
]

#: The version of OpenSubdiv the ``osd`` engine is built against.
OSD_VERSION: str = _subdiv.OSD_VERSION

PathLike = Union[str, "os.PathLike[str]"]


@dataclass(frozen=True)
class Level:
    """One refined level.

    ``points``: ``(V, 3)`` positions (float64, or float32 when refined with
    ``precision="f32"``); ``face_counts``: ``(F,)`` int32 face sizes;
    ``face_indices``: int32 vertices of all faces concatenated, in
    OpenSubdiv's order; ``holes``: ``(F,)`` bool, faces that are holes (left
    out of OBJ output); ``uvs``: ``(M, 2)`` values of face-varying channel 0
    and ``uv_indices`` (one per face corner), or ``None`` without UVs.
    """

    points: np.ndarray
    face_counts: np.ndarray
    face_indices: np.ndarray
    holes: np.ndarray
    uvs: Optional[np.ndarray] = None
    uv_indices: Optional[np.ndarray] = None

    @property
    def vertex_count(self) -> int:
        """Number of vertices."""
        return int(self.points.shape[0])

    @property
    def face_count(self) -> int:
        """Number of faces (holes included)."""
        return int(self.face_counts.shape[0])


@dataclass(frozen=True)
class Limit:
    """Limit positions, both tangents and limit UVs at the last level's vertices."""

    points: np.ndarray
    du: np.ndarray
    dv: np.ndarray
    uvs: Optional[np.ndarray] = None


@dataclass(frozen=True)
class Refinement:
    """Every level of a refinement (``levels[0]`` is the base mesh) and the limit, if asked for."""

    engine: str
    options: Options
    levels: List[Level]
    limit: Optional[Limit] = None

    @property
    def last(self) -> Level:
        """The last level."""
        return self.levels[-1]


@dataclass(frozen=True)
class LevelComparison:
    """How one level of the native and the osd refinements compares (``subdiv compare``'s row)."""

    level: int
    #: Vertex, edge, face and face-vertex counts of the native refinement.
    native_counts: Tuple[int, int, int, int]
    #: The same counts of the osd refinement.
    osd_counts: Tuple[int, int, int, int]
    #: The first face whose vertex list differs, if any.
    first_face_difference: Optional[int]
    #: Whether edge-vertices, sharpness and hole flags are equal.
    tags_equal: bool
    #: Largest distance between corresponding positions.
    max_position_deviation: float
    #: ``max_position_deviation`` over the bounding-box diagonal.
    relative_position_deviation: float
    #: The vertex where the largest deviation occurs.
    worst_vertex: Optional[int]
    #: Whether the face-varying topology is equal.
    fvar_topology_equal: bool
    #: Largest difference between face-varying values.
    max_fvar_deviation: float
    #: At the last level with ``limit=True``: the limit's relative deviation.
    limit_deviation: Optional[float]
    #: Whether the topology agrees exactly.
    topology_equal: bool

    def agrees(self, tolerance: float = 1e-6) -> bool:
        """Whether everything agrees within ``tolerance`` (relative to the bounding-box diagonal)."""
        return (
            self.topology_equal
            and self.relative_position_deviation <= tolerance
            and self.max_fvar_deviation <= tolerance
            and (self.limit_deviation is None or self.limit_deviation <= tolerance)
        )


@dataclass(frozen=True)
class Comparison:
    """The per-level comparison of both engines and how long each took (seconds)."""

    levels: List[LevelComparison]
    native_seconds: float
    osd_seconds: float

    def agrees(self, tolerance: float = 1e-6) -> bool:
        """Whether every level agrees within ``tolerance`` (``subdiv compare``'s exit status 0)."""
        return all(level.agrees(tolerance) for level in self.levels)


@dataclass(frozen=True)
class CsrMatrix:
    """A sparse matrix in CSR form, as ``scipy.sparse.csr_matrix`` takes it.

    Row ``i`` holds ``data[indptr[i]:indptr[i+1]]`` at columns
    ``indices[indptr[i]:indptr[i+1]]``. ``matrix @ base_points`` refines.
    """

    data: np.ndarray
    indices: np.ndarray
    indptr: np.ndarray
    shape: Tuple[int, int]

    def to_scipy(self) -> Any:
        """The matrix as ``scipy.sparse.csr_matrix`` (needs scipy)."""
        import scipy.sparse  # type: ignore[import-untyped]  # only here: scipy is optional

        return scipy.sparse.csr_matrix((self.data, self.indices, self.indptr), shape=self.shape)

    def to_dense(self) -> np.ndarray:
        """The matrix as a dense float64 array (for small tables)."""
        out = np.zeros(self.shape, dtype=np.float64)
        rows = np.repeat(np.arange(self.shape[0]), np.diff(self.indptr))
        np.add.at(out, (rows, self.indices), self.data)
        return out

    def __matmul__(self, points: np.ndarray) -> np.ndarray:
        """Applies the table to ``(columns, width)`` values, in numpy (float64)."""
        points = np.asarray(points, dtype=np.float64)
        rows = np.repeat(np.arange(self.shape[0]), np.diff(self.indptr))
        out = np.zeros((self.shape[0],) + points.shape[1:], dtype=np.float64)
        np.add.at(out, rows, self.data.reshape((-1,) + (1,) * (points.ndim - 1)) * points[self.indices])
        return out


class ObjFile(NamedTuple):
    """What ``read_obj`` returns: the mesh, the options its tags ask for, the reader's warnings."""

    mesh: Mesh
    options: Options
    warnings: List[str]


def refine(
    mesh: Mesh,
    level: int = 2,
    options: Optional[Options] = None,
    engine: str = "native",
    *,
    precision: str = "f64",
    limit: bool = False,
    faces_first: bool = False,
) -> Refinement:
    """Refines ``mesh`` uniformly to ``level`` with ``engine`` (``"native"`` or ``"osd"``).

    Returns every level's points, faces, holes and UVs as numpy arrays, and
    with ``limit=True`` the limit positions, tangents and UVs at the last
    level. ``options`` defaults to ``Options()`` (OpenSubdiv's shape-file
    conventions, as ``subdiv refine``). ``precision="f32"`` interpolates in
    float32 and returns float32 arrays. The GIL is released while refining.
    """
    levels, lim = _subdiv.refine(mesh, level, options, engine, precision, limit, faces_first)
    return Refinement(
        engine=engine,
        options=options if options is not None else Options(),
        levels=[Level(*t) for t in levels],
        limit=Limit(*lim) if lim is not None else None,
    )


def evaluate(
    mesh: Mesh,
    faces: np.ndarray,
    uv: np.ndarray,
    options: Optional[Options] = None,
    isolation: int = 4,
    engine: str = "native",
    *,
    end_caps: str = "gregory-basis",
    single_crease: bool = False,
    inf_sharp: bool = False,
    double: bool = False,
    derivatives: bool = False,
    exact_limit: bool = False,
) -> Union[np.ndarray, Tuple[np.ndarray, np.ndarray, np.ndarray]]:
    """The limit surface of ``mesh`` at ptex faces ``faces`` and coordinates ``uv``.

    As ``subdiv eval``: the mesh refined adaptively to ``isolation`` (0-10),
    its patch table (``end_caps`` ``"none"``, ``"bilinear"``, ``"bspline"``,
    ``"gregory-basis"`` or ``"legacy-gregory"``; ``single_crease``,
    ``inf_sharp`` and ``double`` as ``--single-crease``, ``--inf-sharp`` and
    ``--double``), then ``PatchMap`` and ``EvaluateBasis`` at each location.
    ``faces`` holds ``N`` ptex face numbers (``Far::PtexIndices``), ``uv`` is
    ``(N, 2)`` with coordinates in [0, 1]. Returns ``(N, 3)`` float64
    positions, or ``(positions, du, dv)`` with ``derivatives=True``.

    ``exact_limit=True`` (``--exact-limit``, native engine only) evaluates
    the exact limit surface where OpenSubdiv's ``EvaluateBasis`` departs from
    it: single-crease patches with their sharpness (semi-sharp) instead of
    infinitely sharp, derivatives under non-quad faces with respect to the
    ptex face. The GIL is released while evaluating.
    """
    return _subdiv.evaluate(
        mesh, faces, uv, options, isolation, engine, end_caps,
        single_crease, inf_sharp, double, derivatives, exact_limit,
    )


def compare(
    mesh: Mesh,
    level: int = 2,
    options: Optional[Options] = None,
    *,
    precision: str = "f64",
    limit: bool = False,
    faces_first: bool = False,
) -> Comparison:
    """Refines ``mesh`` with both engines and compares them level by level (``subdiv compare``)."""
    rows, native_seconds, osd_seconds = _subdiv.compare(
        mesh, level, options, precision, limit, faces_first
    )
    levels = [
        LevelComparison(
            **{
                **row,
                "native_counts": tuple(row["native_counts"]),
                "osd_counts": tuple(row["osd_counts"]),
            }
        )
        for row in rows
    ]
    return Comparison(levels=levels, native_seconds=native_seconds, osd_seconds=osd_seconds)


class Refiner:
    """A mesh's topology refined once, for any number of frames.

    ``Refiner(mesh, level=2, options=None, engine="native", faces_first=False,
    full_topology=True)`` refines the topology (GIL released);
    ``interpolate(points)`` then refines a frame of ``(V, width)`` float32 or
    float64 values through every level, reading them in place. The refiner
    can be shared by threads.
    """

    __slots__ = ("_r",)

    def __init__(
        self,
        mesh: Mesh,
        level: int = 2,
        options: Optional[Options] = None,
        engine: str = "native",
        *,
        faces_first: bool = False,
        full_topology: bool = True,
    ) -> None:
        self._r = _subdiv.Refiner(mesh, level, options, engine, faces_first, full_topology)

    @property
    def engine(self) -> str:
        """``"native"`` or ``"osd"``."""
        return self._r.engine

    @property
    def level(self) -> int:
        """The last level."""
        return self._r.level

    def vertex_counts(self) -> List[int]:
        """Number of vertices of every level, base first."""
        return self._r.vertex_counts()

    def topology(self, level: int) -> Tuple[np.ndarray, np.ndarray, np.ndarray]:
        """``(face_counts, face_indices, holes)`` of ``level``."""
        return self._r.topology(level)

    def interpolate(self, points: np.ndarray) -> List[np.ndarray]:
        """Every level's values from base values ``(V, width)``, level 0 first, same dtype."""
        return self._r.interpolate(points)

    def interpolate_last(self, points: np.ndarray) -> np.ndarray:
        """The last level's values from base values (``interpolate(points)[-1]``)."""
        return self._r.interpolate_last(points)

    def interpolate_face_varying(self, values: np.ndarray, channel: int = 0) -> List[np.ndarray]:
        """Every level's face-varying values of ``channel`` (0: UVs) from the mesh's ``(M, width)`` values."""
        return self._r.interpolate_face_varying(values, channel)

    def limit(self, points: np.ndarray) -> Tuple[np.ndarray, np.ndarray, np.ndarray]:
        """``(positions, du, dv)`` at the last level's vertices, from values at the last level."""
        return self._r.limit(points)

    def stencil_table(self) -> CsrMatrix:
        """The ``(last vertices, base vertices)`` stencil matrix: ``table @ base == interpolate_last(base)``."""
        return CsrMatrix(*self._r.stencil_table())

    def limit_stencil_table(self) -> Tuple[CsrMatrix, CsrMatrix, CsrMatrix]:
        """Limit position, du and dv stencils of the last level's vertices from the base vertices."""
        p, du, dv = self._r.limit_stencil_table()
        return CsrMatrix(*p), CsrMatrix(*du), CsrMatrix(*dv)

    def __repr__(self) -> str:
        return repr(self._r)


def read_obj(path: PathLike) -> ObjFile:
    """Reads an OBJ file with OpenSubdiv's ``t`` tags: ``(mesh, options, warnings)``."""
    return ObjFile(*_subdiv.read_obj(os.fspath(path)))


def parse_obj(text: str, name: str = "<string>") -> ObjFile:
    """Parses OBJ text as ``read_obj`` reads a file (errors name ``name`` and the line)."""
    return ObjFile(*_subdiv.parse_obj(text, name))


def write_obj(path: PathLike, data: Union[Mesh, Level], precision: str = "f64") -> None:
    """Writes a ``Mesh`` (with its tags) or a refined ``Level`` (as ``subdiv refine -o``) atomically.

    Numbers are written as C's ``%.17g`` (``precision="f32"``: ``%.9g`` of
    the value rounded to float32), so the file is byte-identical to the
    command line's. The file appears whole or not at all.
    """
    path = os.fspath(path)
    if isinstance(data, Mesh):
        _subdiv.write_mesh_obj(path, data, precision)
    elif isinstance(data, Level):
        _subdiv.write_level_obj(
            path,
            data.points,
            data.face_counts,
            data.face_indices,
            data.holes,
            data.uvs,
            data.uv_indices,
            precision,
        )
    else:
        raise TypeError(f"write_obj writes a Mesh or a Level, not {type(data).__name__}")
