"""USD stages written and read by Pixar's own USD library (`usd-core`, `pxr`):
the `subdiv` command line reads them as Pixar's library does.

Every stage here is authored in code with `pxr` (no downloaded or committed
data) and saved as `.usda`, `.usdc` and `.usdz`. For every mesh prim, the
expected result is built from what `pxr` reports (`UsdGeom.Mesh` getters,
whose `Get()` gives the schema's fallback where nothing is authored;
`UsdGeom.PrimvarsAPI`; `Usd.TimeCode`), mapped to a `subdiv.Mesh` and
`subdiv.Options` by the rules of USD's OpenSubdiv adapter (`pxOsd`, written
again below from USD's documentation, independently of `src/io/usd`), and
refined by OpenSubdiv itself (`subdiv.refine(..., "osd")`). The CLI's OBJ
files must equal those byte for byte; `subdiv compare --json` must list
exactly the subdivided, non-class mesh prims `pxr` traverses; the `.usda`
the CLI writes must read back in `pxr`; malformed stages fail naming the
file, the prim and the attribute, and `--lenient` drops what `pxOsd` drops.

Skipped when `pxr` is missing (`make check-python` installs `usd-core`).
"""

from __future__ import annotations

import json
import math
import pathlib
import subprocess
import zipfile
from dataclasses import dataclass, field
from typing import Callable, Dict, List, Optional, Sequence, Tuple

import numpy as np
import pytest

import subdiv
from conftest import run_cli

pytest.importorskip("pxr")
from pxr import Sdf, Usd, UsdGeom, UsdUtils, Vt  # noqa: E402

INF = UsdGeom.Mesh.SHARPNESS_INFINITE  # 10.0, OpenSubdiv's Sdc::Crease::SHARPNESS_INFINITE
LEVELS = (1, 2)
ENGINES = ("native", "osd")
FORMATS = ("usda", "usdc", "usdz")

# ---------------------------------------------------------------------------
# Meshes generated in code
# ---------------------------------------------------------------------------


@dataclass
class Surface:
    """A polygon mesh with an indexed UV set: faces as vertex lists and, in
    parallel, UV index lists."""

    points: List[Tuple[float, float, float]]
    faces: List[List[int]]
    uvs: List[Tuple[float, float]]
    uv_faces: List[List[int]]

    def counts(self) -> List[int]:
        return [len(f) for f in self.faces]

    def indices(self) -> List[int]:
        return [v for f in self.faces for v in f]

    def uv_indices(self) -> List[int]:
        return [v for f in self.uv_faces for v in f]

    def corner_uvs(self) -> List[Tuple[float, float]]:
        """The UV of every face corner (the same values, not indexed)."""
        return [self.uvs[i] for i in self.uv_indices()]


def _split(corners: list, first_diagonal: bool) -> List[list]:
    a, b, c, d = corners
    return [[a, b, c], [a, c, d]] if first_diagonal else [[a, b, d], [b, c, d]]


def tube(nu: int = 24, nv: int = 16) -> Tuple[Surface, Callable[[int, int], int]]:
    """A bumpy partial torus (300 degrees: open, with two boundary rings),
    closed around its tube with a UV seam there; quads, with a sprinkling of
    quads split into triangles, a hexagon and a pentagon. Returns the surface
    and the vertex id of grid point (i, j)."""
    nu1 = nu + 1

    def vid(i: int, j: int) -> int:
        return i * nv + j % nv

    def uid(i: int, j: int) -> int:
        return i * (nv + 1) + j

    points = []
    for i in range(nu1):
        theta = 5.0 / 3.0 * math.pi * i / nu
        for j in range(nv):
            phi = 2.0 * math.pi * j / nv
            r = 1.0 + 0.18 * math.sin(3 * theta) * math.cos(2 * phi) + 0.07 * math.cos(5 * phi + theta)
            rho = 3.0 + r * math.cos(phi)
            points.append((rho * math.cos(theta), rho * math.sin(theta), r * math.sin(phi) + 0.05 * i))
    uvs = [(i / nu, j / nv) for i in range(nu1) for j in range(nv + 1)]

    grid_faces: List[List[Tuple[int, int]]] = []
    for i in range(nu):
        for j in range(nv):
            quad = [(i, j), (i + 1, j), (i + 1, j + 1), (i, j + 1)]
            if (i, j) == (5, 2):  # a hexagon: quads (5, 2) and (5, 3) without their shared edge
                grid_faces.append([(5, 2), (6, 2), (6, 3), (6, 4), (5, 4), (5, 3)])
            elif (i, j) == (5, 3):
                continue
            elif (i, j) == (15, 9):  # a pentagon: quad (15, 9) and half of quad (15, 10)
                grid_faces.append([(15, 9), (16, 9), (16, 10), (16, 11), (15, 10)])
            elif (i, j) == (15, 10):
                grid_faces.append([(15, 10), (16, 11), (15, 11)])
            elif (3 * i + 5 * j) % 11 == 0 and j not in (0, nv - 1) and i != 8 and i != 7:
                grid_faces.extend(_split(quad, i % 2 == 0))
            else:
                grid_faces.append(quad)
    faces = [[vid(i, j) for i, j in f] for f in grid_faces]
    uv_faces = [[uid(i, j) for i, j in f] for f in grid_faces]
    return Surface(points, faces, uvs, uv_faces), vid


def sheet(nx: int, ny: int, seed: float, triangles: bool = True, seam: Optional[int] = None) -> Surface:
    """A bumpy open grid of nx by ny quads, some split into triangles; its
    UVs indexed, with a seam along column `seam` when given."""
    points = []
    for y in range(ny + 1):
        for x in range(nx + 1):
            z = 0.3 * math.sin(seed + 0.9 * x) * math.cos(0.7 * y - seed) + 0.02 * x * y
            points.append((x + 0.1 * math.sin(seed * y), y + 0.05 * math.cos(seed + x), z))
    uvs = [(x / nx, y / ny) for y in range(ny + 1) for x in range(nx + 1)]
    extra = {}
    if seam is not None:  # the right side of the seam gets its own UVs, shifted
        for y in range(ny + 1):
            extra[y] = len(uvs)
            uvs.append((seam / nx + 0.5, y / ny))

    def vid(x: int, y: int) -> int:
        return y * (nx + 1) + x

    def uid(x: int, y: int, face_x: int) -> int:
        if seam is not None and x == seam and face_x >= seam:
            return extra[y]
        return vid(x, y)

    faces, uv_faces = [], []
    for y in range(ny):
        for x in range(nx):
            quad = [(x, y), (x + 1, y), (x + 1, y + 1), (x, y + 1)]
            parts = _split(quad, (x + y) % 2 == 0) if triangles and (2 * x + 3 * y) % 7 == 1 else [quad]
            for part in parts:
                faces.append([vid(a, b) for a, b in part])
                uv_faces.append([uid(a, b, x) for a, b in part])
    return Surface(points, faces, uvs, uv_faces)


def triangle_sheet(nx: int, ny: int) -> Surface:
    """A bumpy open grid of 2 * nx * ny triangles (for Loop)."""
    s = sheet(nx, ny, 0.4, triangles=False)
    faces, uv_faces = [], []
    for f, u in zip(s.faces, s.uv_faces):
        first = len(faces) % 3 == 0
        faces.extend(_split(f, first))
        uv_faces.extend(_split(u, first))
    return Surface(s.points, faces, s.uvs, uv_faces)


def reversed_faces(faces: Sequence[Sequence[int]]) -> List[List[int]]:
    """Each face from its first corner backwards: the clockwise listing that
    `orientation = "leftHanded"` declares."""
    return [[f[0], *reversed(f[1:])] for f in faces]


# ---------------------------------------------------------------------------
# Authoring with pxr
# ---------------------------------------------------------------------------


def define_mesh(stage: Usd.Stage, path: str, s: Surface, *, faces: Optional[List[List[int]]] = None,
                st: Optional[str] = "indexed", uv_faces: Optional[List[List[int]]] = None) -> UsdGeom.Mesh:
    """A Mesh prim with `s`'s points and faces and, by `st`: an indexed
    `primvars:st` ("indexed"), a non-indexed face-varying
    `primvars:st_faceVarying` ("faceVarying") or none (None)."""
    mesh = UsdGeom.Mesh.Define(stage, path)
    faces = s.faces if faces is None else faces
    mesh.CreatePointsAttr(Vt.Vec3fArray(s.points))
    mesh.CreateFaceVertexCountsAttr(Vt.IntArray([len(f) for f in faces]))
    mesh.CreateFaceVertexIndicesAttr(Vt.IntArray([v for f in faces for v in f]))
    pv_api = UsdGeom.PrimvarsAPI(mesh)
    uv_faces = s.uv_faces if uv_faces is None else uv_faces
    if st == "indexed":
        pv = pv_api.CreatePrimvar("st", Sdf.ValueTypeNames.TexCoord2fArray, UsdGeom.Tokens.faceVarying)
        pv.Set(Vt.Vec2fArray(s.uvs))
        pv.SetIndices(Vt.IntArray([i for f in uv_faces for i in f]))
    elif st == "faceVarying":
        pv = pv_api.CreatePrimvar("st_faceVarying", Sdf.ValueTypeNames.TexCoord2fArray, UsdGeom.Tokens.faceVarying)
        pv.Set(Vt.Vec2fArray(s.corner_uvs() if uv_faces is s.uv_faces else [s.uvs[i] for f in uv_faces for i in f]))
    return mesh


def set_creases(mesh: UsdGeom.Mesh, chains: Sequence[Sequence[int]], sharpnesses: Sequence[float]) -> None:
    mesh.CreateCreaseIndicesAttr(Vt.IntArray([v for c in chains for v in c]))
    mesh.CreateCreaseLengthsAttr(Vt.IntArray([len(c) for c in chains]))
    mesh.CreateCreaseSharpnessesAttr(Vt.FloatArray(list(sharpnesses)))


def set_corners(mesh: UsdGeom.Mesh, vertices: Sequence[int], sharpnesses: Sequence[float]) -> None:
    mesh.CreateCornerIndicesAttr(Vt.IntArray(list(vertices)))
    mesh.CreateCornerSharpnessesAttr(Vt.FloatArray(list(sharpnesses)))


def author_asset(path: pathlib.Path) -> None:
    """The referenced layer: `/Asset`, its default prim, a bumpy sheet with
    triangles and `triangleSubdivisionRule = "smooth"`."""
    stage = Usd.Stage.CreateNew(str(path))
    mesh = define_mesh(stage, "/Asset", sheet(9, 7, 1.3, seam=4))
    mesh.CreateTriangleSubdivisionRuleAttr(UsdGeom.Tokens.smooth)
    set_creases(mesh, [[0, 1, 2, 3, 4]], [1.25])
    stage.SetDefaultPrim(mesh.GetPrim())
    stage.GetRootLayer().Save()


# The mesh prims of the main stage that are subdivided, in traversal order,
# and the ones that are not (subdivisionScheme "none", the class prim).
SUBDIVIDED = [
    "/World/Body",
    "/World/Geo/BodyPerEdge",
    "/World/LeftHanded",
    "/World/FaceVaryingSt",
    "/World/LoopTris",
    "/World/Bilinear",
    "/World/Referenced",
    "/World/Inherited",
    "/World/Animated",
]
NOT_SUBDIVIDED = ["/World/NotSubdivided", "/_MeshClass"]
ANIMATED_TIMES = (1.0, 2.0, 3.0)


def animated_points(base: Surface, t: Optional[float]) -> List[Tuple[float, float, float]]:
    """The animated sheet's points at sample time t (None: the default value)."""
    amplitude = 0.0 if t is None else 0.25 * t
    return [(x, y, z + amplitude * math.sin(x + t if t else x)) for x, y, z in base.points]


def author_main(path: pathlib.Path, asset: str) -> None:
    """The main stage (see SUBDIVIDED): every kind of mesh the task lists."""
    stage = Usd.Stage.CreateNew(str(path))
    world = UsdGeom.Xform.Define(stage, "/World")
    stage.SetDefaultPrim(world.GetPrim())
    UsdGeom.SetStageUpAxis(stage, UsdGeom.Tokens.z)

    # A production-like body: mixed quads, triangles, a hexagon and a pentagon,
    # semi-sharp and infinitely sharp crease chains (one sharpness per crease),
    # corners, holes, an indexed st with a seam, a second face-varying primvar,
    # a constant and a vertex primvar; interpolateBoundary and
    # faceVaryingLinearInterpolation authored, triangleSubdivisionRule not.
    surface, vid = tube()
    body = define_mesh(stage, "/World/Body", surface)
    rings = [[vid(8, j) for j in range(17)],                 # a closed ring, semi-sharp
             [vid(i, 0) for i in range(10, 19)],             # along the seam, infinitely sharp
             [vid(i, 8) for i in range(2, 5)]]               # a short chain, semi-sharp
    # (Sharpnesses below 2 are semi-sharp at the levels compared, 1 and 2.)
    set_creases(body, rings, [1.5, INF, 0.75])
    set_corners(body, [vid(0, 0), vid(14, 5), vid(20, 11), vid(12, 0)], [INF, 0.6, 1.25, 1.8])
    body.CreateHoleIndicesAttr(Vt.IntArray([30, 31, 250]))
    body.CreateInterpolateBoundaryAttr(UsdGeom.Tokens.edgeOnly)
    body.CreateFaceVaryingLinearInterpolationAttr(UsdGeom.Tokens.cornersPlus2)
    pv_api = UsdGeom.PrimvarsAPI(body)
    alt = pv_api.CreatePrimvar("uvAlt", Sdf.ValueTypeNames.Float2Array, UsdGeom.Tokens.faceVarying)
    alt.Set(Vt.Vec2fArray([(0.1 * surface.points[v][0], 0.1 * surface.points[v][1]) for v in surface.indices()]))
    pv_api.CreatePrimvar("displayColor", Sdf.ValueTypeNames.Color3fArray, UsdGeom.Tokens.constant).Set(
        Vt.Vec3fArray([(0.8, 0.4, 0.2)]))
    pv_api.CreatePrimvar("rest", Sdf.ValueTypeNames.Point3fArray, UsdGeom.Tokens.vertex).Set(
        Vt.Vec3fArray(surface.points))

    # The same body under an Xform, one sharpness per crease edge, varying
    # along each chain; every option unauthored (the schema's fallbacks).
    UsdGeom.Xform.Define(stage, "/World/Geo")
    per_edge = define_mesh(stage, "/World/Geo/BodyPerEdge", surface)
    set_creases(per_edge, rings, [0.5 + 0.25 * k for k in range(16)] + [INF] * 8 + [1.0, 3.0])
    set_corners(per_edge, [vid(3, 3), vid(24, 7)], [1.4, INF])
    per_edge.CreateHoleIndicesAttr(Vt.IntArray([100]))

    # Left-handed: faces listed clockwise (from the first corner backwards),
    # the st indices alike; triangleSubdivisionRule smooth, face-varying
    # boundaries, edge-only boundaries.
    s = sheet(10, 8, 0.7, seam=5)
    left = define_mesh(stage, "/World/LeftHanded", s, faces=reversed_faces(s.faces),
                       uv_faces=reversed_faces(s.uv_faces))
    left.CreateOrientationAttr(UsdGeom.Tokens.leftHanded)
    left.CreateTriangleSubdivisionRuleAttr(UsdGeom.Tokens.smooth)
    left.CreateFaceVaryingLinearInterpolationAttr(UsdGeom.Tokens.boundaries)
    left.CreateInterpolateBoundaryAttr(UsdGeom.Tokens.edgeOnly)
    set_creases(left, [[13, 14, 15, 16], [40, 51]], [1.3, 0.5])
    set_corners(left, [0], [INF])

    # UVs only as a non-indexed face-varying `st_faceVarying` (no `st`).
    s = sheet(8, 6, 2.1, seam=3)
    fv = define_mesh(stage, "/World/FaceVaryingSt", s, st="faceVarying")
    fv.CreateFaceVaryingLinearInterpolationAttr(UsdGeom.Tokens.all)

    # Loop on triangles, creases per edge, a corner, indexed st; fallbacks.
    s = triangle_sheet(11, 9)
    loop = define_mesh(stage, "/World/LoopTris", s)
    loop.CreateSubdivisionSchemeAttr(UsdGeom.Tokens.loop)
    set_creases(loop, [[24, 25, 26, 27, 28]], [0.5, 1.0, 1.7, INF])
    set_corners(loop, [0, 11], [INF, 1.5])

    # Bilinear with an authored interpolateBoundary "none" that pxOsd overrides
    # (edgeAndCorner for every bilinear mesh).
    s = sheet(7, 5, 3.3, seam=2)
    bil = define_mesh(stage, "/World/Bilinear", s)
    bil.CreateSubdivisionSchemeAttr(UsdGeom.Tokens.bilinear)
    bil.CreateInterpolateBoundaryAttr(UsdGeom.Tokens.none)
    bil.CreateFaceVaryingLinearInterpolationAttr(UsdGeom.Tokens.none)

    # Reached through a reference to the other layer, with a local (stronger)
    # interpolateBoundary and corners.
    ref = stage.DefinePrim("/World/Referenced", "Mesh")
    ref.GetReferences().AddReference(asset)
    ref_mesh = UsdGeom.Mesh(ref)
    ref_mesh.CreateInterpolateBoundaryAttr(UsdGeom.Tokens.edgeOnly)
    set_corners(ref_mesh, [0, 9], [0.8, INF])

    # Inherits its topology, UVs, creases and interpolateBoundary from a class
    # prim (typed Mesh, abstract: no mesh of its own); its points are local.
    cls = stage.CreateClassPrim("/_MeshClass")
    cls.SetTypeName("Mesh")
    s = sheet(6, 6, 0.2, seam=3)
    cls_mesh = UsdGeom.Mesh(cls)
    cls_mesh.CreateFaceVertexCountsAttr(Vt.IntArray(s.counts()))
    cls_mesh.CreateFaceVertexIndicesAttr(Vt.IntArray(s.indices()))
    cls_mesh.CreatePointsAttr(Vt.Vec3fArray([(0.0, 0.0, 0.0)] * len(s.points)))
    cls_mesh.CreateInterpolateBoundaryAttr(UsdGeom.Tokens.none)
    set_creases(cls_mesh, [[7, 8, 9, 10]], [1.5])
    st = UsdGeom.PrimvarsAPI(cls).CreatePrimvar("st", Sdf.ValueTypeNames.TexCoord2fArray, UsdGeom.Tokens.faceVarying)
    st.Set(Vt.Vec2fArray(s.uvs))
    st.SetIndices(Vt.IntArray(s.uv_indices()))
    inherited = stage.DefinePrim("/World/Inherited", "Mesh")
    inherited.GetInherits().AddInherit("/_MeshClass")
    UsdGeom.Mesh(inherited).CreatePointsAttr(Vt.Vec3fArray(s.points))

    # Time-sampled points (and a default value).
    s = sheet(6, 5, 1.9)
    anim = define_mesh(stage, "/World/Animated", s)
    points = anim.GetPointsAttr()
    points.Set(Vt.Vec3fArray(animated_points(s, None)))
    for t in ANIMATED_TIMES:
        points.Set(Vt.Vec3fArray(animated_points(s, t)), Usd.TimeCode(t))
    anim.CreateFaceVaryingLinearInterpolationAttr(UsdGeom.Tokens.cornersOnly)

    # Not subdivided: skipped.
    flat = define_mesh(stage, "/World/NotSubdivided", sheet(3, 3, 0.5), st=None)
    flat.CreateSubdivisionSchemeAttr(UsdGeom.Tokens.none)

    stage.GetRootLayer().Save()


@pytest.fixture(scope="module")
def stages(tmp_path_factory) -> Dict[str, pathlib.Path]:
    """The main stage as `.usda` (referencing `asset.usda`), `.usdc`
    (`Sdf.Layer.Export` of the same layers, referencing `asset.usdc`) and
    `.usdz` (`UsdUtils.CreateNewUsdzPackage` of the `.usda`, the referenced
    layer packaged with it)."""
    root = tmp_path_factory.mktemp("pixar")
    text, crate, package = root / "text", root / "crate", root / "package"
    for d in (text, crate, package):
        d.mkdir()
    author_asset(text / "asset.usda")
    author_main(text / "main.usda", "./asset.usda")
    # The crate files: the same layers exported by Sdf, the reference
    # retargeted to the exported asset.
    assert Sdf.Layer.FindOrOpen(str(text / "asset.usda")).Export(str(crate / "asset.usdc"))
    layer = Sdf.Layer.FindOrOpen(str(text / "main.usda"))
    assert layer.Export(str(crate / "main.usdc"))
    crate_layer = Sdf.Layer.FindOrOpen(str(crate / "main.usdc"))
    crate_layer.GetPrimAtPath("/World/Referenced").referenceList.ClearEditsAndMakeExplicit()
    crate_layer.GetPrimAtPath("/World/Referenced").referenceList.explicitItems = [Sdf.Reference("./asset.usdc")]
    assert crate_layer.Save()
    assert Sdf.FileFormat.FindByExtension("usdc") == crate_layer.GetFileFormat()
    assert UsdUtils.CreateNewUsdzPackage(Sdf.AssetPath(str(text / "main.usda")), str(package / "main.usdz"))
    assert zipfile.ZipFile(package / "main.usdz").namelist() == ["main.usda", "asset.usda"]
    return {"usda": text / "main.usda", "usdc": crate / "main.usdc", "usdz": package / "main.usdz"}


# ---------------------------------------------------------------------------
# The pxOsd mapping, applied to what pxr reports
# ---------------------------------------------------------------------------

SCHEMES = {"catmullClark": "catmark", "loop": "loop", "bilinear": "bilinear"}
BOUNDARIES = {"none": "none", "edgeOnly": "edge-only", "edgeAndCorner": "edge-and-corner"}
FVARS = {"none": "none", "cornersOnly": "corners-only", "cornersPlus1": "corners-plus1",
         "cornersPlus2": "corners-plus2", "boundaries": "boundaries", "all": "all"}
TRIANGLES = {"catmullClark": "catmark", "smooth": "smooth"}


def _ints(value) -> List[int]:
    return [] if value is None else [int(v) for v in value]


def _floats(value) -> List[float]:
    return [] if value is None else [float(v) for v in value]


@dataclass
class PxrMesh:
    """A mesh prim as pxr reads it, mapped as pxOsd maps it."""

    path: str
    mesh: subdiv.Mesh
    options: subdiv.Options
    uv_name: Optional[str]
    dropped: List[str] = field(default_factory=list)  # what pxOsd drops, as pxOsd warns


def pxosd_creases(indices: List[int], lengths: List[int], weights: List[float], points: int,
                  dropped: List[str]) -> List[Tuple[int, int, float]]:
    """pxOsd's crease rule (refinerFactory.cpp, assignComponentTags): the
    sharpnesses are one per crease when there are as many as creases, else
    one per crease edge; any other count drops every crease ("Invalid length
    of crease sharpnesses"); a crease edge with a vertex out of range is
    skipped; sharpness max(0, s). creaseLengths not adding up to the indices
    is not checked by pxOsd (it reads past the array): every crease is
    dropped, as subdiv documents."""
    if sum(lengths) != len(indices) or any(n < 0 for n in lengths):
        if lengths or indices:
            dropped.append("creaseLengths: every crease")
        return []
    per_edge = len(weights) != len(lengths)
    if per_edge and len(weights) != sum(n - 1 for n in lengths):
        dropped.append("creaseSharpnesses: every crease")
        return []
    out, c, s = [], 0, 0
    for n in lengths:
        for j in range(max(n - 1, 0)):
            v0, v1 = indices[c + j], indices[c + j + 1]
            if 0 <= v0 < points and 0 <= v1 < points:
                w = weights[s]
                out.append((v0, v1, w if w > 0.0 else 0.0))
            else:
                dropped.append(f"creaseIndices: edge {v0}-{v1}")
            if per_edge:
                s += 1
        if not per_edge:
            s += 1
        c += n
    return out


def pxosd_corners(indices: List[int], weights: List[float], points: int,
                  dropped: List[str]) -> List[Tuple[int, float]]:
    """pxOsd's corner rule: as many sharpnesses as corners, or no corner at
    all; a corner whose vertex is out of range is skipped; max(0, s)."""
    if len(weights) != len(indices):
        dropped.append("cornerSharpnesses: every corner")
        return []
    out = []
    for v, w in zip(indices, weights):
        if 0 <= v < points:
            out.append((v, w if w > 0.0 else 0.0))
        else:
            dropped.append(f"cornerIndices: vertex {v}")
    return out


def channel_zero(prim: Usd.Prim, time: Usd.TimeCode):
    """Face-varying channel 0: `primvars:st` when face-varying, else the only
    two-component face-varying primvar. Values and indices as pxr gives them
    (an indexed primvar keeps its indices as the channel's topology; a
    non-indexed one has one value per corner)."""
    fvar = [pv for pv in UsdGeom.PrimvarsAPI(prim).GetPrimvars()
            if pv.GetInterpolation() == UsdGeom.Tokens.faceVarying and pv.HasValue()]
    chosen = [pv for pv in fvar if pv.GetPrimvarName() == "st"]
    if not chosen:
        chosen = [pv for pv in fvar if pv.GetElementSize() == 1 and np.asarray(pv.Get(time)).ndim == 2
                  and np.asarray(pv.Get(time)).shape[1] == 2]
        if len(chosen) != 1:
            return None, None, None
    pv = chosen[0]
    values = np.asarray(pv.Get(time), dtype=np.float32)
    indices = np.asarray(pv.GetIndices(time), dtype=np.int64) if pv.IsIndexed() else None
    return str(pv.GetPrimvarName()), values, indices


def from_pxr(prim: Usd.Prim, time: Usd.TimeCode = Usd.TimeCode.Default()) -> PxrMesh:
    """The subdiv mesh and options of a Mesh prim, from pxr's getters."""
    m = UsdGeom.Mesh(prim)
    scheme = m.GetSubdivisionSchemeAttr().Get(time)
    boundary = m.GetInterpolateBoundaryAttr().Get(time)
    if scheme == "bilinear":
        boundary = "edgeAndCorner"  # pxOsd: "override boundary interpolation mode to be edgeAndCorner"
    options = subdiv.Options(
        scheme=SCHEMES[scheme],
        boundary=BOUNDARIES[boundary],
        fvar=FVARS[m.GetFaceVaryingLinearInterpolationAttr().Get(time)],
        creasing="uniform",
        triangles=TRIANGLES[m.GetTriangleSubdivisionRuleAttr().Get(time)],
    )
    points = np.asarray(m.GetPointsAttr().Get(time), dtype=np.float32)
    counts = np.asarray(m.GetFaceVertexCountsAttr().Get(time), dtype=np.int64)
    indices = np.asarray(m.GetFaceVertexIndicesAttr().Get(time), dtype=np.int64)
    dropped: List[str] = []
    creases = pxosd_creases(_ints(m.GetCreaseIndicesAttr().Get(time)), _ints(m.GetCreaseLengthsAttr().Get(time)),
                            _floats(m.GetCreaseSharpnessesAttr().Get(time)), len(points), dropped)
    corners = pxosd_corners(_ints(m.GetCornerIndicesAttr().Get(time)), _floats(m.GetCornerSharpnessesAttr().Get(time)),
                            len(points), dropped)
    holes = _ints(m.GetHoleIndicesAttr().Get(time))
    uv_name, uvs, uv_indices = channel_zero(prim, time)
    if uvs is not None and uv_indices is None:
        uv_indices = np.arange(len(indices))
    kw = {}
    if creases:
        kw["creases"] = (np.array([[a, b] for a, b, _ in creases]), np.array([w for _, _, w in creases], np.float32))
    if corners:
        kw["corners"] = (np.array([v for v, _ in corners]), np.array([w for _, w in corners], np.float32))
    if holes:
        kw["holes"] = np.array(holes)
    if uvs is not None:
        kw["uvs"], kw["uv_indices"] = uvs, uv_indices
    left = m.GetOrientationAttr().Get(time) == UsdGeom.Tokens.leftHanded
    mesh = subdiv.Mesh(points, counts, indices, left_handed=left, **kw)
    return PxrMesh(str(prim.GetPath()), mesh, options, uv_name, dropped)


def pxr_subdivided_meshes(stage: Usd.Stage) -> List[str]:
    """What pxr traverses (active, defined, not abstract: no class prim) that
    is a Mesh and is subdivided."""
    return [str(p.GetPath()) for p in stage.Traverse()
            if p.IsA(UsdGeom.Mesh) and UsdGeom.Mesh(p).GetSubdivisionSchemeAttr().Get() != UsdGeom.Tokens.none]


def expected_objs(tmp: pathlib.Path, name: str, pm: PxrMesh, levels=LEVELS) -> Dict[int, pathlib.Path]:
    """OpenSubdiv's refinement of the pxr-built mesh, each level as OBJ."""
    r = subdiv.refine(pm.mesh, max(levels), pm.options, "osd")
    out = {}
    for level in levels:
        path = tmp / f"{name}-py-{level}.obj"
        subdiv.write_obj(path, r.levels[level])
        out[level] = path
    return out


def cli_obj(cli, tmp: pathlib.Path, name: str, stage: pathlib.Path, prim: str, level: int, engine: str,
            *extra: str) -> bytes:
    out = tmp / f"{name}-cli-{engine}-{level}.obj"
    run_cli(cli, "refine", str(stage), "--prim", prim, "--level", str(level), "--engine", engine, "-o", str(out),
            *extra)
    return out.read_bytes()


def safe(path: str) -> str:
    return path.strip("/").replace("/", "_")


# ---------------------------------------------------------------------------
# Tests
# ---------------------------------------------------------------------------


def test_pxr_reads_what_was_authored(stages):
    """The stages are what the task asks for, as Pixar's library reads them:
    the same meshes in the three formats; fallbacks where nothing is
    authored; the class prim not traversed."""
    read = {}
    for fmt, path in stages.items():
        stage = Usd.Stage.Open(str(path))
        assert pxr_subdivided_meshes(stage) == SUBDIVIDED, fmt
        for p in NOT_SUBDIVIDED:  # Mesh prims, but one not subdivided and one a class
            assert stage.GetPrimAtPath(p).GetTypeName() == "Mesh", p
        meshes = {p: from_pxr(stage.GetPrimAtPath(p)) for p in SUBDIVIDED}
        read[fmt] = meshes
        body = UsdGeom.Mesh(stage.GetPrimAtPath("/World/Body"))
        assert len(body.GetFaceVertexCountsAttr().Get()) > 300
        assert {3, 4, 5, 6} == set(body.GetFaceVertexCountsAttr().Get())
        assert max(body.GetCreaseLengthsAttr().Get()) > 2
        per_edge = UsdGeom.Mesh(stage.GetPrimAtPath("/World/Geo/BodyPerEdge"))
        lengths = per_edge.GetCreaseLengthsAttr().Get()
        assert len(per_edge.GetCreaseSharpnessesAttr().Get()) == sum(n - 1 for n in lengths) != len(lengths)
        for attr in ("interpolateBoundary", "faceVaryingLinearInterpolation", "triangleSubdivisionRule"):
            assert not per_edge.GetPrim().GetAttribute(attr).HasAuthoredValue()
        assert per_edge.GetInterpolateBoundaryAttr().Get() == "edgeAndCorner"
        assert per_edge.GetFaceVaryingLinearInterpolationAttr().Get() == "cornersPlus1"
        assert per_edge.GetTriangleSubdivisionRuleAttr().Get() == "catmullClark"
        assert meshes["/World/Geo/BodyPerEdge"].options == subdiv.Options(
            boundary="edge-and-corner", fvar="corners-plus1", triangles="catmark")
        bil = UsdGeom.Mesh(stage.GetPrimAtPath("/World/Bilinear"))
        assert bil.GetInterpolateBoundaryAttr().Get() == "none"
        assert meshes["/World/Bilinear"].options.boundary == "edge-and-corner"
        assert meshes["/World/Referenced"].options.boundary == "edge-only"  # the local opinion wins
        assert meshes["/World/Referenced"].options.triangles == "smooth"  # from the referenced layer
        assert meshes["/World/Inherited"].options.boundary == "none"  # from the class
        assert meshes["/World/Inherited"].mesh.creases[0].shape == (3, 2)
        assert stage.GetPrimAtPath("/_MeshClass").IsAbstract()
        assert meshes["/World/FaceVaryingSt"].uv_name == "st_faceVarying"
        assert meshes["/World/Body"].uv_name == "st"
        assert meshes["/World/LeftHanded"].mesh.uv_indices is not None
        anim = UsdGeom.Mesh(stage.GetPrimAtPath("/World/Animated")).GetPointsAttr()
        assert anim.GetTimeSamples() == list(ANIMATED_TIMES)
        for pm in meshes.values():
            assert pm.dropped == []
    for fmt in ("usdc", "usdz"):
        for p in SUBDIVIDED:
            a, b = read["usda"][p], read[fmt][p]
            assert a.mesh == b.mesh and a.options == b.options, (fmt, p)


@pytest.mark.parametrize("fmt", FORMATS)
def test_refine_equals_pxr_and_opensubdiv(cli, stages, tmp_path, fmt):
    """For every subdivided mesh prim: `subdiv refine --prim` (both engines,
    levels 1 and 2) writes the OBJ that OpenSubdiv writes from the mesh pxr
    reads, byte for byte."""
    stage_path = stages[fmt]
    stage = Usd.Stage.Open(str(stage_path))
    mismatches = []
    for path in pxr_subdivided_meshes(stage):
        pm = from_pxr(stage.GetPrimAtPath(path))
        name = f"{fmt}-{safe(path)}"
        expected = expected_objs(tmp_path, name, pm)
        for level in LEVELS:
            for engine in ENGINES:
                got = cli_obj(cli, tmp_path, name, stage_path, path, level, engine)
                if got != expected[level].read_bytes():
                    mismatches.append(f"{path} level {level} engine {engine}")
    assert mismatches == [], f"{stage_path}: the CLI's OBJ differs from pxr + OpenSubdiv for {mismatches}"


def test_left_handed_is_the_clockwise_listing(stages):
    """The left-handed prim (faces clockwise) refines, in OpenSubdiv, exactly
    as the same faces listed counter-clockwise in a right-handed mesh."""
    stage = Usd.Stage.Open(str(stages["usda"]))
    pm = from_pxr(stage.GetPrimAtPath("/World/LeftHanded"))
    counts = pm.mesh.face_counts
    starts = np.concatenate([[0], np.cumsum(counts)[:-1]])
    flip = lambda a: np.concatenate([[a[s], *a[s + 1:s + c][::-1]] for s, c in zip(starts, counts)])  # noqa: E731
    right = subdiv.Mesh(pm.mesh.points, counts, flip(pm.mesh.face_indices), creases=pm.mesh.creases,
                        corners=pm.mesh.corners, uvs=pm.mesh.uvs, uv_indices=flip(pm.mesh.uv_indices))
    a = subdiv.refine(pm.mesh, 2, pm.options, "osd").last
    b = subdiv.refine(right, 2, pm.options, "osd").last
    assert np.array_equal(a.points, b.points)
    assert np.array_equal(a.uvs, b.uvs)


@pytest.mark.parametrize("fmt", FORMATS)
def test_compare_lists_exactly_the_subdivided_meshes(cli, stages, fmt):
    """`subdiv compare --levels 1..2 --json`: one report per subdivided,
    non-class mesh prim pxr traverses, in its order, every one agreeing."""
    stage_path = stages[fmt]
    done = run_cli(cli, "compare", str(stage_path), "--levels", "1..2", "--json")
    reports = json.loads(done.stdout)
    expected = pxr_subdivided_meshes(Usd.Stage.Open(str(stage_path)))
    assert [r["input"] for r in reports] == [f"{stage_path}:{p}" for p in expected]
    # Each prim's options as pxOsd sets them from what pxr reads (the bilinear
    # prim's authored interpolateBoundary "none" overridden: edge-and-corner).
    stage = Usd.Stage.Open(str(stage_path))
    for r, p in zip(reports, expected):
        o = from_pxr(stage.GetPrimAtPath(p)).options
        assert r["options"] == (f"{o.scheme} boundary={o.boundary} fvar={o.fvar} creasing={o.creasing} "
                                f"triangles={o.triangles}"), p
    assert all(r["agrees"] for r in reports), [r["input"] for r in reports if not r["agrees"]]
    for r in reports:
        assert [lv["level"] for lv in r["levels"]] == [1, 2]
        assert all(lv["agrees"] and lv["topology_equal"] for lv in r["levels"]), r["input"]
    assert "/World/NotSubdivided skipped" in done.stderr
    assert "_MeshClass" not in done.stdout + done.stderr


@pytest.mark.parametrize("fmt", FORMATS)
def test_time_samples(cli, stages, tmp_path, fmt):
    """`--time T`: the points as pxr reads them at T with USD's default
    (linear) interpolation — the sample at T, the first before the first and
    the last after the last, interpolated between two (bit for bit: GfLerp's
    rounding); without `--time`, the default value."""
    stage_path = stages[fmt]
    stage = Usd.Stage.Open(str(stage_path))
    assert stage.GetInterpolationType() == Usd.InterpolationTypeLinear
    prim = stage.GetPrimAtPath("/World/Animated")
    cases = [(None, Usd.TimeCode.Default()), (2.0, Usd.TimeCode(2.0)), (2.5, Usd.TimeCode(2.5)),
             (0.0, Usd.TimeCode(0.0)), (9.0, Usd.TimeCode(9.0)), (3.0, Usd.TimeCode(3.0))]
    seen = []
    for t, code in cases:
        pm = from_pxr(prim, code)
        seen.append(pm.mesh.points.tobytes())
        name = f"{fmt}-anim-{t}"
        expected = expected_objs(tmp_path, name, pm)
        extra = () if t is None else ("--time", str(t))
        for level in LEVELS:
            for engine in ENGINES:
                got = cli_obj(cli, tmp_path, name, stage_path, "/World/Animated", level, engine, *extra)
                assert got == expected[level].read_bytes(), f"--time {t} level {level} {engine}"
    assert len(set(seen)) == 5  # default, 2, 2.5 (interpolated), 1 (time 0), 3 (and 9)


def test_composition_extras(cli, tmp_path):
    """Beyond the main stage: an inactive mesh, a variant set (only the
    selected variant's mesh), a payload (loaded, as `Usd.Stage.Open` loads
    it) and an `over` typed Mesh (not defined): the CLI reads the meshes pxr
    traverses, and refines them as OpenSubdiv refines what pxr reads."""
    author_asset(tmp_path / "asset.usda")
    path = tmp_path / "extras.usda"
    stage = Usd.Stage.CreateNew(str(path))
    UsdGeom.Xform.Define(stage, "/World")
    define_mesh(stage, "/World/Active", sheet(3, 3, 0.1))
    define_mesh(stage, "/World/Inactive", sheet(3, 3, 0.2)).GetPrim().SetActive(False)
    holder = stage.DefinePrim("/World/Variant", "Xform")
    variants = holder.GetVariantSets().AddVariantSet("shape")
    for name, seed in (("a", 0.3), ("b", 0.4)):
        variants.AddVariant(name)
        variants.SetVariantSelection(name)
        with variants.GetVariantEditContext():
            define_mesh(stage, f"/World/Variant/{name.upper()}", sheet(3, 2, seed))
    variants.SetVariantSelection("b")
    stage.DefinePrim("/World/Payloaded", "Mesh").GetPayloads().AddPayload("./asset.usda")
    ghost = stage.OverridePrim("/World/Ghost")
    ghost.SetTypeName("Mesh")
    s = sheet(2, 2, 0.5)
    UsdGeom.Mesh(ghost).CreatePointsAttr(Vt.Vec3fArray(s.points))
    UsdGeom.Mesh(ghost).CreateFaceVertexCountsAttr(Vt.IntArray(s.counts()))
    UsdGeom.Mesh(ghost).CreateFaceVertexIndicesAttr(Vt.IntArray(s.indices()))
    stage.GetRootLayer().Save()

    stage = Usd.Stage.Open(str(path))
    expected = pxr_subdivided_meshes(stage)
    assert expected == ["/World/Active", "/World/Variant/B", "/World/Payloaded"]
    reports = json.loads(run_cli(cli, "compare", str(path), "--levels", "1..2", "--json").stdout)
    assert [r["input"] for r in reports] == [f"{path}:{p}" for p in expected]
    assert all(r["agrees"] for r in reports)
    for p in expected:
        pm = from_pxr(stage.GetPrimAtPath(p))
        want = expected_objs(tmp_path, safe(p), pm, levels=(2,))
        for engine in ENGINES:
            assert cli_obj(cli, tmp_path, safe(p), path, p, 2, engine) == want[2].read_bytes(), (p, engine)


def _refined_usda(cli, stages, tmp_path, fmt, *extra):
    stage_path = stages[fmt]
    out = tmp_path / f"refined-{fmt}.usda"
    run_cli(cli, "refine", str(stage_path), "-o", str(out), *extra)
    return stage_path, out


@pytest.mark.parametrize("fmt", FORMATS)
def test_refined_usda_reads_back_in_pxr(cli, stages, tmp_path, fmt):
    """`subdiv refine STAGE -o out.usda` (level 2): pxr opens it; every
    subdivided prim is at its path, `subdivisionScheme = "none"`, with the
    refinement's points and st (rounded to f32: point3f[], texCoord2f[]),
    faces and holes."""
    stage_path, out = _refined_usda(cli, stages, tmp_path, fmt)
    src = Usd.Stage.Open(str(stage_path))
    back = Usd.Stage.Open(str(out))
    assert back is not None
    assert [str(p.GetPath()) for p in back.Traverse() if p.IsA(UsdGeom.Mesh)] == SUBDIVIDED
    for path in SUBDIVIDED:
        pm = from_pxr(src.GetPrimAtPath(path))
        r = subdiv.refine(pm.mesh, 2, pm.options, "native").last
        m = UsdGeom.Mesh(back.GetPrimAtPath(path))
        assert m.GetSubdivisionSchemeAttr().Get() == "none", path
        points = m.GetPointsAttr().Get()
        assert points is not None and len(points) == len(r.points), path
        # point3f[]: the refinement's f64 points rounded to f32.
        f32 = np.float32
        assert np.array_equal(np.asarray(points, dtype=f32), r.points.astype(f32)), path
        assert list(m.GetFaceVertexCountsAttr().Get()) == list(r.face_counts), path
        assert list(m.GetFaceVertexIndicesAttr().Get()) == list(r.face_indices), path
        assert list(m.GetHoleIndicesAttr().Get() or []) == list(np.flatnonzero(r.holes)), path
        assert m.GetOrientationAttr().Get() == "rightHanded", path
        st = UsdGeom.PrimvarsAPI(m).GetPrimvar(pm.uv_name or "st")
        if pm.uv_name is None:
            assert not st, path
        else:
            assert st.GetInterpolation() == "faceVarying", path
            assert np.array_equal(np.asarray(st.Get(), dtype=f32), r.uvs.astype(f32)), path
            assert list(st.GetIndices()) == list(r.uv_indices), path
    body = UsdGeom.PrimvarsAPI(back.GetPrimAtPath("/World/Body"))
    assert body.GetPrimvar("uvAlt").GetInterpolation() == "faceVarying"


def _schema_type_report(stage: Usd.Stage) -> List[str]:
    """What a user meets reading the refined meshes: attributes whose authored
    type is not the schema's (Pixar's validator `AttributeTypeMismatch`),
    points that do not come back as the schema's VtVec3fArray, extents pxr
    cannot compute, UVs not typed texCoord2f[]."""
    from pxr import UsdValidation

    problems = []
    validator = UsdValidation.ValidationRegistry().GetOrLoadValidatorByName("usdValidation:AttributeTypeMismatch")
    for error in UsdValidation.ValidationContext([validator]).Validate(stage):
        problems.append(error.GetMessage())
    for prim in stage.Traverse():
        if not prim.IsA(UsdGeom.Mesh):
            continue
        m = UsdGeom.Mesh(prim)
        points = m.GetPointsAttr().Get()
        if not isinstance(points, Vt.Vec3fArray):
            problems.append(f"{prim.GetPath()}.points: Get() returns {type(points).__name__}, not Vec3fArray")
        if UsdGeom.Boundable.ComputeExtentFromPlugins(m, Usd.TimeCode.Default()) is None:
            problems.append(f"{prim.GetPath()}: UsdGeom.Boundable.ComputeExtentFromPlugins fails")
        st = UsdGeom.PrimvarsAPI(prim).GetPrimvar("st")
        if st and st.GetTypeName() != Sdf.ValueTypeNames.TexCoord2fArray:
            problems.append(f"{prim.GetPath()}.primvars:st is {st.GetTypeName()}, not texCoord2f[]")
    return problems


def test_refined_usda_f32_has_the_schema_types(cli, stages, tmp_path):
    """With `--precision f32` the refined layer uses UsdGeomMesh's types:
    nothing for a user to trip on."""
    _, out = _refined_usda(cli, stages, tmp_path, "usda", "--precision", "f32")
    assert _schema_type_report(Usd.Stage.Open(str(out))) == []


def test_refined_usda_default_precision_has_the_schema_types(cli, stages, tmp_path):
    """What a user does: `subdiv refine STAGE -o out.usda` (f64), then reads
    it with pxr: the points are UsdGeomMesh's point3f[] (and st texCoord2f[]),
    with no type mismatch for USD's validator, and extents compute."""
    _, out = _refined_usda(cli, stages, tmp_path, "usda")
    problems = _schema_type_report(Usd.Stage.Open(str(out)))
    assert problems == [], "\n".join(problems)


# ---------------------------------------------------------------------------
# Malformed stages
# ---------------------------------------------------------------------------


def _bad_base(stage: Usd.Stage) -> UsdGeom.Mesh:
    UsdGeom.Xform.Define(stage, "/World")
    define_mesh(stage, "/World/Good", sheet(3, 3, 0.1))
    return define_mesh(stage, "/World/Bad", sheet(5, 4, 0.6, seam=2))


@dataclass
class Malformed:
    name: str
    attribute: str
    author: Callable[[UsdGeom.Mesh], None]
    lenient: bool  # --lenient drops it (a crease or corner) and succeeds


def _lengths_not_summing(m: UsdGeom.Mesh) -> None:
    set_creases(m, [[0, 1, 2], [6, 7]], [2.0, 3.0])
    m.GetCreaseLengthsAttr().Set(Vt.IntArray([3, 3]))  # 6, for 5 indices


def _corner_sharpness_count(m: UsdGeom.Mesh) -> None:
    set_corners(m, [0, 5], [2.0])
    set_creases(m, [[6, 7, 8]], [1.5])


def _face_index_out_of_range(m: UsdGeom.Mesh) -> None:
    indices = list(m.GetFaceVertexIndicesAttr().Get())
    m.GetFaceVertexIndicesAttr().Set(Vt.IntArray([99] + indices[1:]))


MALFORMED = [
    Malformed("crease-lengths-sum", "creaseLengths", _lengths_not_summing, True),
    Malformed("crease-sharpness-count", "creaseSharpnesses",
              lambda m: set_creases(m, [[0, 1, 2], [6, 7]], [1.0, 2.0, 3.0, 4.0]), True),
    Malformed("corner-sharpness-count", "cornerSharpnesses", _corner_sharpness_count, True),
    Malformed("crease-index-out-of-range", "creaseIndices",
              lambda m: set_creases(m, [[0, 1, 99, 3], [12, 13, 14]], [2.0, INF]), True),
    Malformed("corner-index-out-of-range", "cornerIndices",
              lambda m: set_corners(m, [-1, 0, 99, 29], [1.0, 2.0, 3.0, INF]), True),
    Malformed("unknown-scheme", "subdivisionScheme",
              lambda m: m.CreateSubdivisionSchemeAttr().Set("catmark"), False),
    Malformed("unknown-boundary", "interpolateBoundary",
              lambda m: m.CreateInterpolateBoundaryAttr().Set("edgeAndCorners"), False),
    Malformed("face-index-out-of-range", "faceVertexIndices", _face_index_out_of_range, False),
    # pxOsd skips a hole whose face does not exist ("Set hole cannot find
    # face"); subdiv documents every malformed attribute other than creases
    # and corners as an error, --lenient or not.
    Malformed("hole-index-out-of-range", "holeIndices",
              lambda m: m.CreateHoleIndicesAttr(Vt.IntArray([1, 99])), False),
]


@pytest.mark.parametrize("case", MALFORMED, ids=lambda c: c.name)
def test_malformed(cli, tmp_path, case):
    """Exit code 1 and an error naming the file, the prim and the attribute;
    with `--lenient`, a malformed crease or corner is dropped with a warning,
    as pxOsd drops it, and the rest refines as OpenSubdiv refines what pxr
    reads (other malformed attributes stay errors)."""
    path = tmp_path / f"{case.name}.usda"
    stage = Usd.Stage.CreateNew(str(path))
    case.author(_bad_base(stage))
    stage.GetRootLayer().Save()
    # pxr reads the authored values back as they were written (the raw tokens too).
    assert stage.GetPrimAtPath("/World/Bad").GetAttribute(case.attribute).HasAuthoredValue()

    strict = subprocess.run([str(cli), "refine", str(path)], capture_output=True, text=True)
    assert strict.returncode == 1, strict
    assert str(path) in strict.stderr and "/World/Bad" in strict.stderr and case.attribute in strict.stderr, \
        strict.stderr
    out = tmp_path / "lenient.obj"
    lenient = subprocess.run([str(cli), "refine", str(path), "--lenient", "--prim", "/World/Bad", "--level", "2",
                              "-o", str(out)], capture_output=True, text=True)
    if not case.lenient:
        assert lenient.returncode == 1, lenient
        assert "/World/Bad" in lenient.stderr and case.attribute in lenient.stderr, lenient.stderr
        return
    assert lenient.returncode == 0, lenient.stderr
    assert "warning" in lenient.stderr and f"/World/Bad.{case.attribute}" in lenient.stderr, lenient.stderr
    reread = Usd.Stage.Open(str(path))
    pm = from_pxr(reread.GetPrimAtPath("/World/Bad"))
    assert pm.dropped, "pxOsd drops something here"
    expected = expected_objs(tmp_path, case.name, pm, levels=(2,))
    assert out.read_bytes() == expected[2].read_bytes()
