"""The Python API itself: meshes in and out, options, dtypes, OBJ round trips."""

from __future__ import annotations

import numpy as np
import pytest

import subdiv

QUAD = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], dtype=np.float64)


def test_unit_quad_values():
    mesh = subdiv.Mesh(QUAD, [4], [0, 1, 2, 3])
    r = subdiv.refine(mesh, 1, subdiv.Options(boundary="edge-and-corner"))
    last = r.last
    assert last.points.shape == (9, 3) and last.points.dtype == np.float64
    # OpenSubdiv's order: vertex points (corners stay put with edge-and-corner
    # boundaries), the face point, then edge points; faces first on request.
    edges = [[0.5, 0, 0], [1, 0.5, 0], [0.5, 1, 0], [0, 0.5, 0]]
    assert last.points.tolist() == QUAD.tolist() + [[0.5, 0.5, 0]] + edges
    assert last.face_indices.tolist() == [0, 5, 4, 8, 5, 1, 6, 4, 4, 6, 2, 7, 8, 4, 7, 3]
    ff = subdiv.refine(mesh, 1, subdiv.Options(boundary="edge-and-corner"), faces_first=True).last
    assert ff.points.tolist() == [[0.5, 0.5, 0]] + edges + QUAD.tolist()
    assert ff.face_indices.tolist() == [5, 1, 0, 4, 1, 6, 2, 0, 0, 2, 7, 3, 4, 0, 3, 8]
    assert last.face_counts.tolist() == [4, 4, 4, 4] and last.face_counts.dtype == np.int32
    assert last.face_indices.dtype == np.int32 and last.face_indices.shape == (16,)
    assert last.holes.shape == (4,) and last.holes.dtype == np.bool_ and not last.holes.any()
    assert r.levels[0].vertex_count == 4 and r.last.face_count == 4


def test_inputs_of_every_int_and_float_dtype_and_lists():
    ref = subdiv.refine(subdiv.Mesh(QUAD, [4], [0, 1, 2, 3]), 2).last.points
    for fdt in [np.float32, np.float64]:
        for idt in [np.int32, np.int64, np.uint32]:
            m = subdiv.Mesh(QUAD.astype(fdt), np.array([4], idt), np.array([0, 1, 2, 3], idt))
            assert np.array_equal(subdiv.refine(m, 2).last.points, ref)
    m = subdiv.Mesh(QUAD.tolist(), [4], [0, 1, 2, 3])
    assert np.array_equal(subdiv.refine(m, 2).last.points, ref)
    # Non-contiguous views are read (copied once) correctly.
    wide = np.zeros((4, 6))
    wide[:, ::2] = QUAD
    m = subdiv.Mesh(wide[:, ::2], [4], [0, 1, 2, 3])
    assert np.array_equal(subdiv.refine(m, 2).last.points, ref)


def test_mesh_properties_round_trip():
    mesh = subdiv.Mesh(
        QUAD,
        [3, 3],
        [0, 1, 2, 0, 2, 3],
        creases=(np.array([[0, 1], [1, 2]]), np.array([2.5, 10.0])),
        corners=([3], 1.5),
        holes=[1],
        uvs=QUAD[:, :2] * 0.5,
        uv_indices=[0, 1, 2, 0, 2, 3],
    )
    edges, sharpness = mesh.creases
    assert edges.tolist() == [[0, 1], [1, 2]] and sharpness.tolist() == [2.5, 10.0]
    vertices, corner_sharpness = mesh.corners
    assert vertices.tolist() == [3] and corner_sharpness.tolist() == [1.5]
    assert mesh.holes.tolist() == [1]
    assert np.array_equal(mesh.uvs, QUAD[:, :2] * 0.5)
    assert mesh.uv_indices.tolist() == [0, 1, 2, 0, 2, 3]
    assert mesh.face_counts.tolist() == [3, 3] and mesh.vertex_count == 4 and mesh.face_count == 2
    assert np.array_equal(mesh.points, QUAD)
    assert "4 vertices, 2 faces, 2 creases, 1 corners, 1 holes" in repr(mesh)
    # Without uv_indices, one UV per vertex.
    per_vertex = subdiv.Mesh(QUAD, [4], [0, 1, 2, 3], uvs=QUAD[:, :2])
    assert per_vertex.uv_indices.tolist() == [0, 1, 2, 3]


def test_obj_round_trip(tmp_path):
    mesh = subdiv.shapes.corpus()[0][1]
    for name, m in subdiv.shapes.corpus()[::9]:
        path = tmp_path / f"{name}.obj"
        subdiv.write_obj(path, m)
        back = subdiv.read_obj(path)
        assert back.mesh == m, name
        assert back.warnings == []
    text = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\nt interpolateboundary 1/0/0 1\nt crease 2/1/0 0 1 3\n"
    parsed = subdiv.parse_obj(text)
    assert parsed.options == subdiv.Options(boundary="edge-and-corner")
    assert parsed.mesh.creases[1].tolist() == [3.0]
    assert mesh != parsed.mesh


def test_write_level_refuses_inconsistent_arrays(tmp_path):
    last = subdiv.refine(subdiv.Mesh(QUAD, [4], [0, 1, 2, 3]), 1).last
    path = tmp_path / "level.obj"
    with pytest.raises(subdiv.SubdivError, match="add up to"):
        subdiv.write_obj(path, subdiv.Level(last.points, last.face_counts[:2], last.face_indices, last.holes))
    with pytest.raises(subdiv.SubdivError):
        subdiv.write_obj(path, subdiv.Level(last.points, last.face_counts, last.face_indices, last.holes[:2]))
    assert not path.exists()
    subdiv.write_obj(path, last)
    assert path.read_text().count("\nf ") + path.read_text().startswith("f ") == 4


def test_options():
    o = subdiv.Options()
    assert (o.scheme, o.boundary, o.fvar, o.creasing, o.triangles) == ("catmark", "edge-only", "all", "uniform", "catmark")
    assert subdiv.Options.sdc_defaults().boundary == "none"
    assert o.replace(scheme="loop", fvar="boundaries") == subdiv.Options(scheme="loop", fvar="boundaries")
    assert hash(o) == hash(subdiv.Options())
    assert subdiv.Options.CHOICES["fvar"] == ["none", "corners-only", "corners-plus1", "corners-plus2", "boundaries", "all"]
    assert "boundary='edge-only'" in repr(o) or 'boundary="edge-only"' in repr(o)
    # The defaults are the CLI's: refine with None and with Options() agree.
    cube = subdiv.shapes.builtin("cube")
    assert np.array_equal(subdiv.refine(cube, 2).last.points, subdiv.refine(cube, 2, subdiv.Options()).last.points)
    sdc = subdiv.refine(subdiv.shapes.grid(2, 2), 1, subdiv.Options.sdc_defaults())
    assert sdc.last.holes.all()  # boundary "none": the grid's boundary faces are holes


def test_shapes():
    assert subdiv.shapes.torus(100, 100).face_count == 10000
    assert subdiv.shapes.grid(3, 2).uvs.shape == (12, 2)
    with pytest.raises(subdiv.SubdivError, match="unknown shape"):
        subdiv.shapes.builtin("teapot")
    with pytest.raises(subdiv.SubdivError, match="quads"):
        subdiv.shapes.torus(100000, 100000)


def test_outputs_own_their_memory():
    r = subdiv.refine(subdiv.shapes.builtin("cube"), 2)
    pts = r.last.points
    assert pts.flags["C_CONTIGUOUS"] and pts.flags["WRITEABLE"]
    pts[0] = 99.0  # writable, and no other result shares it
    assert not np.array_equal(subdiv.refine(subdiv.shapes.builtin("cube"), 2).last.points[0], pts[0])


def test_csr_to_scipy_when_available():
    scipy = pytest.importorskip("scipy")
    r = subdiv.Refiner(subdiv.shapes.builtin("cube"), 2)
    m = r.stencil_table().to_scipy()
    assert m.shape == (98, 8)
    assert np.allclose(m @ subdiv.shapes.builtin("cube").points, r.interpolate_last(subdiv.shapes.builtin("cube").points))
    assert scipy is not None


def test_readme_example_runs():
    """The README's Python example, run as it is written."""
    import pathlib
    import re

    readme = pathlib.Path(__file__).resolve().parents[2] / "README.md"
    block = re.search(r"```python\n(.*?)```", readme.read_text(), re.S)
    assert block is not None
    scope: dict = {}
    exec(compile(block.group(1), "README.md", "exec"), scope)
    assert scope["native"].last.points.shape == (258, 3)
