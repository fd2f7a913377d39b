"""Many frames through one Refiner, and threads refining at once."""

from __future__ import annotations

import threading
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


def test_the_gil_is_released_while_refining():
    """A Python thread keeps running while the main thread refines: with the
    GIL held it could not run at all during the call."""
    mesh = subdiv.shapes.torus(60, 60)
    subdiv.refine(mesh, 3)  # warm up
    ticks = 0
    started = threading.Event()
    stop = threading.Event()

    def count() -> None:
        nonlocal ticks
        started.set()
        while not stop.is_set():
            ticks += 1

    thread = threading.Thread(target=count)
    thread.start()
    started.wait()
    before = ticks
    for _ in range(3):
        subdiv.refine(mesh, 3)
    during = ticks - before
    stop.set()
    thread.join()
    assert during > 1000, f"the counting thread ran {during} times during the refinements"
