"""native == osd: every array of both engines identical, bit for bit."""

from __future__ import annotations

import numpy as np
import pytest

import subdiv
from conftest import is_triangles


def assert_levels_equal(a: subdiv.Refinement, b: subdiv.Refinement, what: str) -> None:
    assert len(a.levels) == len(b.levels), what
    for k, (x, y) in enumerate(zip(a.levels, b.levels)):
        for field in ["points", "face_counts", "face_indices", "holes", "uvs", "uv_indices"]:
            u, v = getattr(x, field), getattr(y, field)
            if u is None or v is None:
                assert u is None and v is None, f"{what} level {k} {field}"
                continue
            assert u.dtype == v.dtype and u.shape == v.shape, f"{what} level {k} {field}"
            assert np.array_equal(u, v), f"{what} level {k} {field}"
    if a.limit is not None or b.limit is not None:
        for field in ["points", "du", "dv", "uvs"]:
            u, v = getattr(a.limit, field), getattr(b.limit, field)
            assert (u is None) == (v is None)
            if u is not None:
                assert np.array_equal(u, v), f"{what} limit {field}"


@pytest.mark.parametrize("level", [1, 3])
def test_corpus_native_equals_osd(corpus, level):
    for name, mesh in corpus:
        options = subdiv.Options()
        native = subdiv.refine(mesh, level, options, "native")
        osd = subdiv.refine(mesh, level, options, "osd")
        assert_levels_equal(native, osd, name)
        if is_triangles(mesh):
            loop = subdiv.Options(scheme="loop")
            assert_levels_equal(
                subdiv.refine(mesh, level, loop, "native"), subdiv.refine(mesh, level, loop, "osd"), name
            )


def test_corpus_limits_f32_and_faces_first(corpus):
    for name, mesh in corpus[::4]:
        for kw in [dict(limit=True), dict(precision="f32"), dict(faces_first=True)]:
            native = subdiv.refine(mesh, 2, engine="native", **kw)
            osd = subdiv.refine(mesh, 2, engine="osd", **kw)
            assert_levels_equal(native, osd, f"{name} {kw}")
    f32 = subdiv.refine(subdiv.shapes.builtin("cube-uv"), 2, precision="f32")
    assert f32.last.points.dtype == np.float32 and f32.last.uvs.dtype == np.float32


def test_compare_agrees_exactly_on_the_corpus(corpus):
    for name, mesh in corpus[::5]:
        c = subdiv.compare(mesh, 2, limit=True)
        assert c.agrees(0.0), name
        assert [lvl.level for lvl in c.levels] == [0, 1, 2]
        assert c.levels[-1].limit_deviation == 0.0
        assert c.native_seconds > 0 and c.osd_seconds > 0


@pytest.mark.parametrize("engine", ["native", "osd"])
def test_refiner_equals_refine(corpus, engine):
    for name, mesh in corpus[::6]:
        r = subdiv.refine(mesh, 2, engine=engine, limit=True)
        refiner = subdiv.Refiner(mesh, 2, engine=engine)
        levels = refiner.interpolate(mesh.points)
        assert len(levels) == 3
        for lvl, pts in zip(r.levels, levels):
            assert np.array_equal(lvl.points, pts), name
        assert np.array_equal(refiner.interpolate_last(mesh.points), r.last.points)
        counts, indices, holes = refiner.topology(2)
        assert np.array_equal(counts, r.last.face_counts) and np.array_equal(indices, r.last.face_indices)
        assert np.array_equal(holes, r.last.holes)
        assert refiner.vertex_counts() == [lvl.vertex_count for lvl in r.levels]
        p, du, dv = refiner.limit(levels[-1])
        assert np.array_equal(p, r.limit.points) and np.array_equal(du, r.limit.du)
        assert np.array_equal(dv, r.limit.dv)
        if mesh.uvs is not None:
            uvs = refiner.interpolate_face_varying(mesh.uvs)
            for lvl, values in zip(r.levels, uvs):
                assert np.array_equal(lvl.uvs, values), name


def test_stencil_tables_native_equals_osd_and_refine():
    mesh = subdiv.shapes.builtin("torus")
    tables = {e: subdiv.Refiner(mesh, 2, engine=e) for e in ["native", "osd"]}
    a, b = (tables[e].stencil_table() for e in ["native", "osd"])
    assert a.shape == b.shape == (tables["native"].vertex_counts()[-1], mesh.vertex_count)
    for field in ["data", "indices", "indptr"]:
        assert np.array_equal(getattr(a, field), getattr(b, field)), field
    assert a.indices.dtype == np.int32 and a.indptr.dtype == np.int32 and a.data.dtype == np.float64
    # The table refines as the refiner does (to rounding: another order of additions).
    refined = tables["native"].interpolate_last(mesh.points)
    assert np.allclose(a @ mesh.points, refined, rtol=0, atol=1e-12)
    dense = a.to_dense()
    assert np.allclose(dense.sum(axis=1), 1.0, atol=1e-12)  # affine weights
    la, lb = tables["native"].limit_stencil_table(), tables["osd"].limit_stencil_table()
    for x, y in zip(la, lb):
        assert x.shape == y.shape
        assert np.allclose(x @ mesh.points, y @ mesh.points, rtol=0, atol=1e-12)
    p, _, _ = tables["native"].limit(refined)
    assert np.allclose(la[0] @ mesh.points, p, rtol=0, atol=1e-12)


def test_left_handed_meshes_refine_as_their_counter_clockwise_originals(corpus):
    """A face list written clockwise (first corner kept, UV indices alike) with
    left_handed=True refines, in both engines, exactly as the original
    counter-clockwise mesh: every level, level 0 included (the engines' own
    reading of the input)."""
    for name, mesh in corpus:
        counts = mesh.face_counts
        indices, uv_indices = mesh.face_indices.copy(), mesh.uv_indices
        uv_indices = None if uv_indices is None else uv_indices.copy()
        start = 0
        for n in counts:
            for array in (indices, uv_indices):
                if array is not None:
                    array[start + 1 : start + n] = array[start + 1 : start + n][::-1].copy()
            start += n
        flipped = subdiv.Mesh(
            mesh.points,
            counts,
            indices,
            creases=mesh.creases if len(mesh.creases[1]) else None,
            corners=mesh.corners if len(mesh.corners[1]) else None,
            holes=mesh.holes if len(mesh.holes) else None,
            uvs=mesh.uvs,
            uv_indices=uv_indices,
            left_handed=True,
        )
        assert flipped.left_handed and not mesh.left_handed
        for engine in ["native", "osd"]:
            a = subdiv.refine(mesh, 2, subdiv.Options(), engine)
            b = subdiv.refine(flipped, 2, subdiv.Options(), engine)
            assert_levels_equal(a, b, f"{name} {engine}")
