"""Shared fixtures: the `subdiv` command-line program the tests compare with,
and the library's conformance corpus."""

from __future__ import annotations

import os
import pathlib
import subprocess

import pytest

import subdiv

ROOT = pathlib.Path(__file__).resolve().parents[2]


@pytest.fixture(scope="session")
def cli() -> pathlib.Path:
    """The `subdiv` binary: $SUBDIV_CLI, else the repository's target/debug/subdiv
    (`make check-python` builds it first). Missing is a failure, not a skip."""
    path = pathlib.Path(os.environ.get("SUBDIV_CLI", ROOT / "target" / "debug" / "subdiv"))
    assert path.is_file(), f"{path} is missing: run `cargo build --all-features` first"
    return path


@pytest.fixture(scope="session")
def corpus() -> list:
    """The library's corpus (subdiv::shapes::corpus), as (name, Mesh) pairs."""
    shapes = subdiv.shapes.corpus()
    assert len(shapes) > 50
    return shapes


def is_triangles(mesh: subdiv.Mesh) -> bool:
    """Whether every face is a triangle (Loop applies)."""
    return bool((mesh.face_counts == 3).all())


def run_cli(cli: pathlib.Path, *args: str) -> subprocess.CompletedProcess:
    """Runs the CLI; a failure shows its stderr."""
    done = subprocess.run([str(cli), *args], capture_output=True, text=True)
    assert done.returncode == 0, f"subdiv {' '.join(args)}: {done.stderr}"
    return done
