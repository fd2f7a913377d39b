"""Errors are exceptions carrying the library's messages, never crashes."""

from __future__ import annotations

import numpy as np
import pytest

import subdiv

QUAD = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], dtype=np.float64)


def quad(**kw) -> subdiv.Mesh:
    return subdiv.Mesh(QUAD, [4], [0, 1, 2, 3], **kw)


def test_exception_hierarchy():
    for e in [subdiv.MeshError, subdiv.ObjError, subdiv.LevelError, subdiv.OsdError]:
        assert issubclass(e, subdiv.SubdivError)
    assert issubclass(subdiv.SubdivError, ValueError)


def test_bad_indices_carry_the_rust_messages():
    with pytest.raises(subdiv.MeshError, match=r"^invalid mesh: face 0 corner 2: vertex index 7 is out of range \(the mesh has 4 vertices\)$"):
        subdiv.Mesh(QUAD, [4], [0, 1, 7, 3])
    with pytest.raises(subdiv.MeshError, match=r"face_indices\[1\] is -1"):
        subdiv.Mesh(QUAD, [4], np.array([0, -1, 2, 3], dtype=np.int64))
    with pytest.raises(subdiv.MeshError, match="face 0 has 2 vertices; a face needs at least 3"):
        subdiv.Mesh(QUAD, [2, 2], [0, 1, 2, 3])
    with pytest.raises(subdiv.MeshError, match="add up to 5 face corners but face_indices has 4"):
        subdiv.Mesh(QUAD, [5], [0, 1, 2, 3])
    with pytest.raises(subdiv.MeshError, match="hole 0"):
        quad(holes=[3])
    with pytest.raises(subdiv.MeshError, match="crease 0"):
        quad(creases=(np.array([[0, 9]]), 2.0))
    with pytest.raises(subdiv.MeshError, match="corner 0"):
        quad(corners=([9], [1.0]))
    with pytest.raises(subdiv.MeshError, match="not finite|NaN|nan"):
        subdiv.Mesh(np.array([[0, 0, np.nan], [1, 0, 0], [1, 1, 0]], float), [3], [0, 1, 2])
    with pytest.raises(subdiv.MeshError):
        quad(uvs=np.zeros((2, 2)), uv_indices=[0, 1, 5, 0])
    with pytest.raises(subdiv.MeshError, match="uv_indices given without uvs"):
        quad(uv_indices=[0, 1, 2, 3])
    with pytest.raises(subdiv.MeshError, match="the loop scheme needs triangles"):
        subdiv.refine(quad(), 1, subdiv.Options(scheme="loop"))
    with pytest.raises(subdiv.MeshError, match="no faces"):
        subdiv.refine(subdiv.Mesh(np.zeros((0, 3)), np.zeros(0, int), np.zeros(0, int)), 1)


def test_wrong_shapes():
    with pytest.raises(subdiv.SubdivError, match=r"points must have the shape \(N, 3\), not \[4, 2\]"):
        subdiv.Mesh(QUAD[:, :2], [4], [0, 1, 2, 3])
    with pytest.raises(subdiv.SubdivError, match="points must have the shape"):
        subdiv.Mesh(QUAD.ravel(), [4], [0, 1, 2, 3])
    with pytest.raises(subdiv.SubdivError, match="face_indices must have the shape"):
        subdiv.Mesh(QUAD, [4], [[0, 1, 2, 3]])
    with pytest.raises(subdiv.SubdivError, match="creases indices must have the shape"):
        quad(creases=([0, 1], 1.0))
    with pytest.raises(subdiv.MeshError, match="sharpness must be one number or 1 numbers"):
        quad(creases=([[0, 1]], [1.0, 2.0]))
    with pytest.raises(TypeError, match="pair"):
        quad(creases=[[0, 1]])
    refiner = subdiv.Refiner(quad(), 1)
    with pytest.raises(subdiv.SubdivError, match="buffer has 9 values, expected 12"):
        refiner.interpolate(QUAD[:3])
    with pytest.raises(subdiv.SubdivError, match=r"shape \(N, width\)"):
        refiner.interpolate(QUAD.ravel())


def test_wrong_dtypes():
    with pytest.raises(TypeError, match="points must be a float32 or float64 array, not int64"):
        subdiv.Mesh(QUAD.astype(np.int64), [4], [0, 1, 2, 3])
    with pytest.raises(TypeError, match="face_indices must be an integer array"):
        subdiv.Mesh(QUAD, [4], np.array([0, 1, 2, 3], dtype=np.float64))
    with pytest.raises(TypeError, match="complex128"):
        subdiv.Refiner(quad(), 1).interpolate(QUAD.astype(np.complex128))
    with pytest.raises(TypeError):
        subdiv.Mesh("not an array", [4], [0, 1, 2, 3])
    with pytest.raises(TypeError):
        subdiv.refine("not a mesh", 1)


def test_levels_out_of_range():
    with pytest.raises(subdiv.LevelError, match="refinement level -1 refused"):
        subdiv.refine(quad(), -1)
    with pytest.raises(subdiv.LevelError, match="refinement level 11 refused: the deepest supported level is 10"):
        subdiv.refine(quad(), 11, engine="osd")
    with pytest.raises(subdiv.LevelError, match="refinement level 4294967295 refused"):
        subdiv.Refiner(quad(), 2**40)
    with pytest.raises(subdiv.LevelError):
        subdiv.compare(quad(), -3)
    # A level the memory cannot hold is refused before allocating.
    with pytest.raises(subdiv.LevelError, match="refinement level 10 refused"):
        subdiv.refine(subdiv.shapes.torus(300, 300), 10)
    with pytest.raises(subdiv.SubdivError, match="level 5 is not refined"):
        subdiv.Refiner(quad(), 1).topology(5)


def test_bad_names():
    with pytest.raises(subdiv.SubdivError, match=r"unknown Scheme 'wobbly' \(expected one of: bilinear, catmark, loop\)"):
        subdiv.Options(scheme="wobbly")
    with pytest.raises(subdiv.SubdivError, match="unknown engine 'opensubdiv'"):
        subdiv.refine(quad(), 1, engine="opensubdiv")
    with pytest.raises(subdiv.SubdivError, match="f16"):
        subdiv.refine(quad(), 1, precision="f16")


def test_limit_needs_full_topology():
    r = subdiv.Refiner(quad(), 1, full_topology=False)
    pts = r.interpolate_last(QUAD)
    with pytest.raises(subdiv.SubdivError, match="needs full topology"):
        r.limit(pts)


def test_obj_errors_name_file_and_line(tmp_path):
    with pytest.raises(subdiv.ObjError, match=r"mesh.obj:2"):
        subdiv.parse_obj("v 0 0 0\nv 1 zero 0\n", "mesh.obj")
    with pytest.raises(subdiv.ObjError, match="missing.obj"):
        subdiv.read_obj(tmp_path / "missing.obj")
    # An unwritable path raises OSError and leaves nothing behind.
    target = tmp_path / "no-such-dir" / "out.obj"
    with pytest.raises(OSError):
        subdiv.write_obj(target, quad())
    assert not target.parent.exists()
    with pytest.raises(TypeError):
        subdiv.write_obj(tmp_path / "x.obj", "text")
