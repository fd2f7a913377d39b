"""The ten-line check run in a fresh virtual environment holding only the wheel and numpy."""
import numpy as np
import subdiv

points = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [0.5, 0.5, 1]], dtype=np.float64)
mesh = subdiv.Mesh(points, face_counts=[4, 3, 3, 3, 3], face_indices=[3, 2, 1, 0, 0, 1, 4, 1, 2, 4, 2, 3, 4, 3, 0, 4])
native, osd = (subdiv.refine(mesh, level=3, engine=e) for e in ("native", "osd"))
for a, b in zip(native.levels, osd.levels):
    assert np.array_equal(a.points, b.points) and np.array_equal(a.face_indices, b.face_indices)
assert native.last.points.shape == (258, 3), native.last.points.shape
print(f"subdiv {subdiv.__file__}: native == osd at levels 0-3, {native.last.face_count} faces (OpenSubdiv {subdiv.OSD_VERSION})")
