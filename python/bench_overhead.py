"""Overhead of the Python layer (issue #27): `subdiv.refine(torus, level=2)`
against the same `Engine::refine` call timed inside Rust, on the 10k-quad
torus (`subdiv::shapes::torus(100, 100)`), in one process, runs interleaved.

Run with a release build installed (`make check-python` installs a debug
one; build and install a release wheel first):
    cd python && ../.venv/bin/maturin build --release --auditwheel skip
    ../.venv/bin/pip install --force-reinstall --no-deps target/wheels/subdiv-*.whl
    cd .. && .venv/bin/python python/bench_overhead.py [--runs N]
The Python time includes everything a caller pays: argument parsing, the
refinement (GIL released), handing every level's arrays to numpy and the
dataclasses. Prints medians and the overhead in percent.
"""

from __future__ import annotations

import argparse
import os
import pathlib
import platform
import statistics
import sys
import time

# This file sits next to the package's sources (python/subdiv/, without the
# compiled extension): import the installed package, not them.
HERE = pathlib.Path(__file__).resolve().parent
sys.path = [p for p in sys.path if pathlib.Path(p or ".").resolve() != HERE]

import subdiv  # noqa: E402
from subdiv import _subdiv  # noqa: E402


def cpu() -> str:
    """The processor's model name (Linux), or what platform knows."""
    try:
        for line in open("/proc/cpuinfo", encoding="utf-8"):
            if line.startswith("model name"):
                return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or platform.machine()


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=41, help="timed runs of each (default 41)")
    parser.add_argument("--level", type=int, default=2)
    args = parser.parse_args()
    mesh = subdiv.shapes.torus(100, 100)
    print(f"torus 100x100 ({mesh.face_count} quads), level {args.level}, {args.runs} runs each, "
          f"{cpu()} ({os.cpu_count()} cores), Python {platform.python_version()}, "
          f"{time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}")
    for engine in ["native", "osd"]:
        rust, python = [], []
        # Warm-up runs, untimed.
        subdiv.refine(mesh, args.level, engine=engine)
        _subdiv.time_rust_refine(mesh, args.level, None, engine, 1)
        def rust_run() -> None:
            rust.extend(_subdiv.time_rust_refine(mesh, args.level, None, engine, 1))

        def python_run() -> None:
            start = time.perf_counter()
            r = subdiv.refine(mesh, args.level, engine=engine)
            del r  # the arrays' memory is freed, as the Rust run drops its result
            python.append(time.perf_counter() - start)

        # Interleaved, in the order ABBA so that neither always follows the other.
        for k in range(args.runs):
            for run in (rust_run, python_run) if k % 2 == 0 else (python_run, rust_run):
                run()
        rm, pm = statistics.median(rust), statistics.median(python)
        print(f"{engine:6}: Rust call {rm * 1e3:8.3f} ms, Python subdiv.refine {pm * 1e3:8.3f} ms, "
              f"overhead {(pm - rm) * 1e3:+.3f} ms = {100 * (pm - rm) / rm:+.2f}%  "
              f"(min {min(rust) * 1e3:.3f} / {min(python) * 1e3:.3f} ms)")


if __name__ == "__main__":
    main()
