"""examples/python/compare_engines.py runs and writes its plot (when matplotlib is installed)."""

from __future__ import annotations

import pathlib
import subprocess
import sys

import pytest

import subdiv

EXAMPLE = pathlib.Path(__file__).resolve().parents[2] / "examples" / "python" / "compare_engines.py"


def test_compare_engines_example(tmp_path):
    pytest.importorskip("matplotlib")
    mesh = tmp_path / "cube.obj"
    subdiv.write_obj(mesh, subdiv.shapes.builtin("cube-uv"))
    plot = tmp_path / "plot.png"
    done = subprocess.run(
        [sys.executable, str(EXAMPLE), str(mesh), "--levels", "3", "--runs", "1", "--out", str(plot)],
        capture_output=True,
        text=True,
        cwd=tmp_path,
    )
    assert done.returncode == 0, done.stderr
    assert "arrays bit-identical: True" in done.stdout
    assert plot.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
