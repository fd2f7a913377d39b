"""`subdiv.evaluate`: the limit surface through patch tables, as `subdiv eval`
computes it, with OpenSubdiv's basis or the exact limit (`exact_limit=True`,
`--exact-limit`)."""

from __future__ import annotations

import numpy as np
import pytest

import subdiv
from conftest import run_cli

# A unit cube, its edge 0-1 semi-sharp (2.5): with single-crease patches the
# table marks the crease's patches, which OpenSubdiv's EvaluateBasis
# evaluates infinitely sharp and the exact limit with their sharpness.
CUBE = np.array(
    [[-0.5, -0.5, 0.5], [0.5, -0.5, 0.5], [-0.5, 0.5, 0.5], [0.5, 0.5, 0.5],
     [-0.5, 0.5, -0.5], [0.5, 0.5, -0.5], [-0.5, -0.5, -0.5], [0.5, -0.5, -0.5]]
)
FACES = [0, 1, 3, 2, 2, 3, 5, 4, 4, 5, 7, 6, 6, 7, 1, 0, 1, 7, 5, 3, 6, 0, 2, 4]
# Every ptex face (the cube's 6 quads) on a 5 x 5 grid of (u, v).
GRID = np.linspace(0.0, 1.0, 5)
FACE_IDS = np.repeat(np.arange(6), 25)
UV = np.tile(np.array([[u, v] for v in GRID for u in GRID]), (6, 1))


def creased_cube() -> subdiv.Mesh:
    return subdiv.Mesh(CUBE, [4] * 6, FACES, creases=([[0, 1]], 2.5))


def cli_eval(cli, tmp_path, mesh, *flags):
    """`subdiv eval` of `mesh` at (FACE_IDS, UV): its numbers, one row per location."""
    src = tmp_path / "cube.obj"
    subdiv.write_obj(src, mesh)
    at = tmp_path / "at.txt"
    at.write_text("".join(f"{f} {float(u)!r} {float(v)!r}\n" for f, (u, v) in zip(FACE_IDS, UV)))
    out = tmp_path / "out.txt"
    run_cli(cli, "eval", str(src), "--at", str(at), "-o", str(out), *flags)
    return np.array([[float(x) for x in line.split()] for line in out.read_text().splitlines()])


def test_exact_limit_departs_from_evaluate_basis_on_single_crease_patches(cli, tmp_path):
    mesh = creased_cube()
    common = dict(isolation=3, single_crease=True, derivatives=True)
    p, du, dv = subdiv.evaluate(mesh, FACE_IDS, UV, **common)
    ep, edu, edv = subdiv.evaluate(mesh, FACE_IDS, UV, exact_limit=True, **common)
    assert p.shape == ep.shape == edu.shape == (150, 3) and ep.dtype == np.float64
    # Away from the crease both are the same B-splines and Gregory patches,
    # bit for bit; on the faces of the crease (0 and 3) the semi-sharp
    # surface departs from the infinitely sharp one OpenSubdiv's basis
    # evaluates.
    moved = np.abs(np.hstack([ep - p, edu - du, edv - dv])).max(axis=1)
    near = (FACE_IDS == 0) | (FACE_IDS == 3)
    assert (moved[~near] == 0).all()
    assert moved[near].max() > 1e-3
    # The exact limit is the surface a deep isolation converges to (a table
    # of isolation 10 without single-crease patches: 1.7e-11 from it when
    # measured, against 2.5e-2 for OpenSubdiv's basis).
    deep = subdiv.evaluate(mesh, FACE_IDS, UV, isolation=10)
    assert np.abs(deep - ep).max() < 1e-9
    assert np.abs(deep - p).max() > 2e-2
    # Each equals the native library's result as `subdiv eval` prints it
    # (17 significant digits: every f64 bit).
    flags = ["--isolation", "3", "--single-crease", "--derivatives"]
    for ours, extra in [((p, du, dv), []), ((ep, edu, edv), ["--exact-limit"])]:
        rows = cli_eval(cli, tmp_path, mesh, *flags, *extra)
        assert np.array_equal(np.hstack(ours), rows)


def test_evaluate_positions_and_refusals():
    mesh = creased_cube()
    p = subdiv.evaluate(mesh, [0, 1], [[0.25, 0.5], [1.0, 1.0]], isolation=2)
    assert isinstance(p, np.ndarray) and p.shape == (2, 3)
    with pytest.raises(subdiv.SubdivError, match="exact-limit"):
        subdiv.evaluate(mesh, [0], [[0.5, 0.5]], engine="osd", exact_limit=True)
    with pytest.raises(subdiv.SubdivError, match="one face per"):
        subdiv.evaluate(mesh, [0, 1], [[0.5, 0.5]])
    with pytest.raises(subdiv.SubdivError):
        subdiv.evaluate(mesh, [0], [[1.5, 0.5]])
    with pytest.raises(subdiv.SubdivError, match="end-cap"):
        subdiv.evaluate(mesh, [0], [[0.5, 0.5]], end_caps="round")
