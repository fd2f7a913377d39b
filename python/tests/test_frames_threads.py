"""Many frames through one Refiner, and threads refining at once."""

from __future__ import annotations

import re
import threading
import time
from concurrent.futures import ThreadPoolExecutor

import numpy as np

import subdiv


def frame(points: np.ndarray, t: int) -> np.ndarray:
    """A deformation of the base points at frame `t`."""
    return points * (1.0 + 0.01 * t) + np.sin(0.1 * t + points[:, [1, 2, 0]])


def test_hundred_frames_equal_whole_refinements():
    mesh = subdiv.shapes.torus(12, 8)
    base = mesh.points
    counts, indices = mesh.face_counts, mesh.face_indices
    for engine in ["native", "osd"]:
        refiner = subdiv.Refiner(mesh, 2, engine=engine)
        table = refiner.stencil_table()
        for t in range(100):
            points = frame(base, t)
            last = refiner.interpolate_last(points)
            assert last.shape == (refiner.vertex_counts()[-1], 3)
            if t % 10 == 0:
                # The same frame as a mesh of its own, refined whole: identical.
                whole = subdiv.refine(subdiv.Mesh(points, counts, indices), 2, engine=engine)
                assert np.array_equal(whole.last.points, last)
                assert np.allclose(table @ points, last, rtol=0, atol=1e-12)
            # float32 frames stay float32 and round like the f32 refinement.
            if t % 25 == 0:
                f32 = refiner.interpolate_last(points.astype(np.float32))
                assert f32.dtype == np.float32
                whole32 = subdiv.refine(subdiv.Mesh(points, counts, indices), 2, engine=engine, precision="f32")
                assert np.array_equal(whole32.last.points, f32)


def test_threads_refine_concurrently_with_identical_results():
    meshes = [subdiv.shapes.torus(10 + k, 8 + k) for k in range(8)]
    serial = [subdiv.refine(m, 2, engine=("native", "osd")[k % 2]) for k, m in enumerate(meshes)]

    def work(k: int) -> subdiv.Refinement:
        return subdiv.refine(meshes[k], 2, engine=("native", "osd")[k % 2])

    with ThreadPoolExecutor(max_workers=4) as pool:
        for _ in range(3):
            results = list(pool.map(work, range(len(meshes))))
            for a, b in zip(serial, results):
                assert np.array_equal(a.last.points, b.last.points)
                assert np.array_equal(a.last.face_indices, b.last.face_indices)


def test_one_refiner_shared_by_threads():
    mesh = subdiv.shapes.torus(16, 12)
    refiner = subdiv.Refiner(mesh, 2)
    frames = [frame(mesh.points, t) for t in range(16)]
    expected = [refiner.interpolate_last(f) for f in frames]
    with ThreadPoolExecutor(max_workers=4) as pool:
        got = list(pool.map(refiner.interpolate_last, frames))
    for a, b in zip(expected, got):
        assert np.array_equal(a, b)


def coverage(call) -> float:
    """The fraction of `call()`'s duration (in the main thread) during which
    another Python thread ran: 5 ms buckets holding a tick of a counting
    thread. A call that holds the GIL lets no other Python thread run except
    in the Python code around it, when the interpreter switches threads."""
    stamps: list = []
    started = threading.Event()
    stop = threading.Event()

    def count() -> None:
        started.set()
        while not stop.is_set():
            stamps.append(time.perf_counter())

    thread = threading.Thread(target=count)
    thread.start()
    started.wait()
    time.sleep(0.01)
    t0 = time.perf_counter()
    call()
    t1 = time.perf_counter()
    stop.set()
    thread.join()
    bucket = 0.005
    n = max(1, int((t1 - t0) / bucket))
    hit = {int((t - t0) / bucket) for t in stamps if t0 <= t < t0 + n * bucket}
    return len(hit) / n


def test_the_gil_is_released_while_refining():
    mesh = subdiv.shapes.torus(100, 100)
    refiner = subdiv.Refiner(mesh, 4)
    subdiv.refine(mesh, 3)  # warm up
    points = frame(mesh.points, 1)

    # Best of three: on a loaded machine (CI beside other builds) the
    # counting thread can lose its core for a while whatever the GIL does;
    # one measurement in three with the core is enough to tell.
    def best(call) -> float:
        return max(coverage(call) for _ in range(3))

    assert best(lambda: subdiv.refine(mesh, 3)) > 0.4
    assert best(lambda: subdiv.refine(mesh, 3, engine="osd")) > 0.4
    assert best(lambda: refiner.interpolate(points)) > 0.4
    # The measure itself: a call that holds the GIL (a regular expression
    # backtracking in C, about as long) leaves the other thread little time.
    assert coverage(lambda: re.match(r"(a|aa)*c", "a" * 30)) < 0.25
