"""Random, mostly malformed inputs: every call either works or raises one of
subdiv's exceptions (or TypeError), never crashes the interpreter; when both
engines accept a mesh, their arrays are identical."""

from __future__ import annotations

import numpy as np

import subdiv

ACCEPTED = (subdiv.SubdivError, TypeError)


def random_mesh_args(rng: np.random.Generator) -> dict:
    n = int(rng.integers(0, 9))
    faces = int(rng.integers(0, 6))
    counts = rng.integers(2, 6, size=faces)
    if rng.random() < 0.1:
        counts = counts - rng.integers(0, 3, size=faces)  # sizes below 3, even negative
    total = int(np.clip(counts, 0, None).sum())
    if rng.random() < 0.1:
        total += int(rng.integers(-2, 3))  # sizes that do not add up
    low = -1 if rng.random() < 0.1 else 0  # negative indices now and then
    high = max(n + (1 if rng.random() < 0.2 else 0), 1)  # one past the last vertex too
    indices = rng.integers(low, high, size=max(total, 0))
    points = rng.normal(size=(n, 3))
    if n and rng.random() < 0.05:
        points[rng.integers(0, n)] = np.inf
    args = dict(points=points, face_counts=counts, face_indices=indices)
    if rng.random() < 0.3 and n >= 2:
        k = int(rng.integers(1, 4))
        args["creases"] = (rng.integers(0, n + 1, size=(k, 2)), rng.uniform(-1, 12, size=k))
    if rng.random() < 0.2 and n >= 1:
        args["corners"] = (rng.integers(0, n + 1, size=2), rng.uniform(0, 12, size=2))
    if rng.random() < 0.2:
        args["holes"] = rng.integers(0, faces + 1, size=1)
    if rng.random() < 0.2:
        m = int(rng.integers(1, 6))
        args["uvs"] = rng.random((m, 2))
        args["uv_indices"] = rng.integers(0, m + (1 if rng.random() < 0.2 else 0), size=max(total, 0))
    return args


def test_random_meshes_never_crash_and_engines_agree():
    rng = np.random.default_rng(27)
    accepted = refined = 0
    for _ in range(1500):
        args = random_mesh_args(rng)
        try:
            mesh = subdiv.Mesh(
                args["points"],
                args["face_counts"],
                args["face_indices"],
                **{k: v for k, v in args.items() if k not in ("points", "face_counts", "face_indices")},
            )
        except ACCEPTED:
            continue
        accepted += 1
        level = int(rng.integers(0, 4))
        options = subdiv.Options(
            scheme=str(rng.choice(["catmark", "bilinear", "loop"])),
            boundary=str(rng.choice(subdiv.Options.CHOICES["boundary"])),
            fvar=str(rng.choice(subdiv.Options.CHOICES["fvar"])),
        )
        results = {}
        for engine in ["native", "osd"]:
            try:
                results[engine] = subdiv.refine(mesh, level, options, engine, limit=bool(rng.random() < 0.3))
            except ACCEPTED:
                pass
        if len(results) == 2:
            refined += 1
            for a, b in zip(results["native"].levels, results["osd"].levels):
                assert np.array_equal(a.points, b.points)
                assert np.array_equal(a.face_indices, b.face_indices)
                assert (a.uvs is None) == (b.uvs is None)
                if a.uvs is not None:
                    assert np.array_equal(a.uvs, b.uvs) and np.array_equal(a.uv_indices, b.uv_indices)
    # The generator makes both kinds: refused meshes and refined ones.
    print(f"{accepted} meshes accepted, {refined} refined by both engines")
    assert 200 < accepted < 1500 and refined > 100, (accepted, refined)


def test_random_arrays_of_every_dtype_and_shape():
    rng = np.random.default_rng(7)
    refiner = subdiv.Refiner(subdiv.shapes.builtin("cube-uv"), 2)
    dtypes = [np.float64, np.float32, np.int32, np.int64, np.uint8, np.bool_, np.complex64, np.float16, object]
    for _ in range(200):
        shape = tuple(int(d) for d in rng.integers(0, 10, size=int(rng.integers(0, 4))))
        dtype = dtypes[int(rng.integers(0, len(dtypes)))]
        a = np.zeros(shape, dtype=dtype)
        for call in (
            lambda: refiner.interpolate(a),
            lambda: refiner.limit(a),
            lambda: refiner.interpolate_face_varying(a),
            lambda: subdiv.Mesh(a, [3], [0, 1, 2]),
            lambda: subdiv.Mesh(np.zeros((3, 3)), a, [0, 1, 2]),
        ):
            try:
                call()
            except ACCEPTED:
                pass
