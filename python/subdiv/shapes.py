"""Meshes generated in code (the library's ``subdiv::shapes``): test and benchmark inputs."""

from __future__ import annotations

from typing import List, Tuple

from . import _subdiv

__all__ = ["builtin", "corpus", "grid", "torus"]


def corpus() -> List[Tuple[str, "_subdiv.Mesh"]]:
    """The conformance corpus: ``[(name, mesh), ...]`` (n-gons, poles, boundaries,
    creases, corners, holes, non-manifold features, UV seams)."""
    return _subdiv.corpus()


def builtin(name: str) -> "_subdiv.Mesh":
    """A shape of ``subdiv refine --builtin``: cube, cube-uv, grid, torus or tetrahedron."""
    return _subdiv.builtin(name)


def torus(nu: int, nv: int) -> "_subdiv.Mesh":
    """A closed torus of ``nu`` x ``nv`` quads (``torus(100, 100)`` is the 10k-quad benchmark torus)."""
    return _subdiv.torus(nu, nv)


def grid(nx: int, ny: int) -> "_subdiv.Mesh":
    """An open grid of ``nx`` x ``ny`` unit quads in the z = 0 plane, with per-vertex UVs."""
    return _subdiv.grid(nx, ny)
