"""Python results equal the `subdiv` command line's, bit for bit: every mesh of
the corpus is written with `subdiv.write_obj`, refined by `subdiv refine -o`,
and the file the CLI writes is compared byte for byte with the one Python
writes from `subdiv.refine`, and value by value after reading it back."""

from __future__ import annotations

import json

import numpy as np
import pytest

import subdiv
from conftest import is_triangles, run_cli

# (CLI flags, the same options in Python) tried on every mesh they apply to.
OPTION_SETS = [
    ([], subdiv.Options()),
    (
        ["--boundary", "edge-and-corner", "--fvar", "corners-plus1", "--creasing", "chaikin"],
        subdiv.Options(boundary="edge-and-corner", fvar="corners-plus1", creasing="chaikin"),
    ),
    (["--scheme", "bilinear", "--boundary", "none"], subdiv.Options(scheme="bilinear", boundary="none")),
    (["--triangles", "smooth", "--fvar", "none"], subdiv.Options(triangles="smooth", fvar="none")),
]


def cli_vs_python(cli, tmp_path, name, mesh, flags, options, level, engine, extra=(), precision="f64", limit=False):
    """Refines through the CLI and through Python; asserts both files and their values equal."""
    src = tmp_path / f"{name}.obj"
    subdiv.write_obj(src, mesh)
    out_cli = tmp_path / f"{name}-cli.obj"
    out_py = tmp_path / f"{name}-py.obj"
    args = ["refine", str(src), "-o", str(out_cli), "--level", str(level), "--engine", engine, *flags, *extra]
    run_cli(cli, *args)
    r = subdiv.refine(mesh, level, options, engine, precision=precision, limit=limit)
    last = r.last
    if limit:
        last = subdiv.Level(r.limit.points, last.face_counts, last.face_indices, last.holes,
                            r.limit.uvs, last.uv_indices)
    subdiv.write_obj(out_py, last, precision=precision)
    assert out_py.read_bytes() == out_cli.read_bytes(), f"{name}: files differ"
    # The CLI's numbers, read back, are the Python arrays' (%.17g round-trips f64).
    back = subdiv.read_obj(out_cli).mesh
    if precision == "f64":
        assert np.array_equal(back.points, last.points)
    else:
        assert np.array_equal(back.points.astype(np.float32), last.points)
    keep = ~last.holes
    starts = np.concatenate([[0], np.cumsum(last.face_counts)[:-1]])
    expected = np.concatenate(
        [last.face_indices[s : s + c] for s, c, k in zip(starts, last.face_counts, keep) if k]
    )
    assert np.array_equal(back.face_indices, expected)
    assert (back.uvs is None) == (last.uvs is None)
    if last.uvs is not None:
        assert np.array_equal(back.uvs.astype(last.uvs.dtype), last.uvs)
        assert np.array_equal(back.uv_indices, np.concatenate(
            [last.uv_indices[s : s + c] for s, c, k in zip(starts, last.face_counts, keep) if k]))


@pytest.mark.parametrize("engine", ["native", "osd"])
def test_corpus_level_2_default_options(cli, corpus, tmp_path, engine):
    for name, mesh in corpus:
        cli_vs_python(cli, tmp_path, name, mesh, [], subdiv.Options(), 2, engine)


def test_corpus_option_sets_and_loop(cli, corpus, tmp_path):
    for name, mesh in corpus[::3]:
        for k, (flags, options) in enumerate(OPTION_SETS):
            cli_vs_python(cli, tmp_path, f"{name}-{k}", mesh, flags, options, 1, "native")
        if is_triangles(mesh):
            cli_vs_python(cli, tmp_path, f"{name}-loop", mesh, ["--scheme", "loop"],
                          subdiv.Options(scheme="loop"), 2, "osd")


@pytest.mark.parametrize("level", [0, 1, 3])
def test_levels_f32_and_limit(cli, corpus, tmp_path, level):
    for name, mesh in corpus[::7]:
        cli_vs_python(cli, tmp_path, f"{name}-f32", mesh, [], subdiv.Options(), level, "native",
                      extra=["--precision", "f32"], precision="f32")
        cli_vs_python(cli, tmp_path, f"{name}-limit", mesh, [], subdiv.Options(), level, "native",
                      extra=["--limit"], limit=True)


def test_builtin_shapes_as_the_cli_knows_them(cli, tmp_path):
    for name in ["cube", "cube-uv", "grid", "torus", "tetrahedron"]:
        out = tmp_path / f"{name}.obj"
        run_cli(cli, "refine", "--builtin", name, "--level", "2", "-o", str(out))
        py = tmp_path / f"{name}-py.obj"
        subdiv.write_obj(py, subdiv.refine(subdiv.shapes.builtin(name), 2).last)
        assert py.read_bytes() == out.read_bytes()


def test_compare_equals_the_cli_compare(cli, corpus, tmp_path):
    """`subdiv.compare` gives `subdiv compare --json`'s rows (counts, first
    differing face, deviations, agreement) on meshes of the corpus."""
    for name, mesh in corpus[::5]:
        src = tmp_path / f"{name}.obj"
        subdiv.write_obj(src, mesh)
        done = run_cli(cli, "compare", str(src), "--levels", "0..3", "--json")
        rows = json.loads(done.stdout)["levels"]
        c = subdiv.compare(mesh, 3)
        assert len(rows) == len(c.levels) == 4
        for row, lvl in zip(rows, c.levels):
            assert row["level"] == lvl.level
            assert tuple(row["native_counts"]) == lvl.native_counts
            assert tuple(row["osd_counts"]) == lvl.osd_counts
            assert row["first_differing_face"] == lvl.first_face_difference
            assert row["topology_equal"] == lvl.topology_equal
            assert row["max_abs_deviation"] == lvl.max_position_deviation
            assert row["max_rel_deviation"] == lvl.relative_position_deviation
            assert row["fvar_deviation"] == lvl.max_fvar_deviation
            assert row["agrees"] == lvl.agrees(1e-6)
    cube = subdiv.compare(subdiv.shapes.builtin("cube-uv"), 3)
    assert [lvl.native_counts[0] for lvl in cube.levels] == [8, 26, 98, 386]
