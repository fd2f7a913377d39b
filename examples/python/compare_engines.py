# %% [markdown]
# # Comparing subdiv's two engines from Python
#
# A notebook-style script (cells marked `# %%`, runnable as a whole with
# `python examples/python/compare_engines.py [MESH.obj] [--out PLOT.png]`):
# load a mesh, refine it with the native engine and with OpenSubdiv, compare
# them level by level, and plot the deviation and the timing with
# matplotlib. Needs the `subdiv` module (`pip install ./python`) and
# matplotlib (only this example does).

# %%
from __future__ import annotations

import argparse
import time

import numpy as np

import subdiv

parser = argparse.ArgumentParser(description="compare subdiv's native engine with OpenSubdiv")
parser.add_argument("mesh", nargs="?", help="an OBJ file (default: a generated 40x30 torus with creases)")
parser.add_argument("--levels", type=int, default=4, help="deepest level (default 4)")
parser.add_argument("--runs", type=int, default=5, help="timed runs per engine and level (default 5)")
parser.add_argument("--out", help="write the plot to this file instead of showing it")
args = parser.parse_args()

# %% [markdown]
# ## Load a mesh
# An OBJ file with OpenSubdiv's tags gives the mesh and the options its
# tags ask for; without one, a torus is generated in code.

# %%
if args.mesh:
    mesh, options, warnings = subdiv.read_obj(args.mesh)
    for w in warnings:
        print("warning:", w)
    name = args.mesh
else:
    torus = subdiv.shapes.torus(40, 30)
    ring = np.arange(40)
    mesh = subdiv.Mesh(
        torus.points,
        torus.face_counts,
        torus.face_indices,
        creases=(np.stack([ring, (ring + 1) % 40], axis=1), 2.5),
    )
    options = subdiv.Options(creasing="chaikin")
    name = "torus 40x30, a semi-sharp crease loop"
print(f"{name}: {mesh.vertex_count} vertices, {mesh.face_count} faces, {options}")

# %% [markdown]
# ## Compare the engines level by level
# `subdiv.compare` refines with both engines and returns `subdiv compare`'s
# rows as dataclasses; `subdiv.refine` gives the arrays themselves, which
# we also compare directly.

# %%
comparison = subdiv.compare(mesh, args.levels, options, limit=True)
for row in comparison.levels:
    print(
        f"level {row.level}: {row.native_counts[0]} vertices, {row.native_counts[2]} faces, "
        f"topology equal {row.topology_equal}, max deviation {row.max_position_deviation:.3g} "
        f"(relative {row.relative_position_deviation:.3g}), limit {row.limit_deviation}"
    )
native = subdiv.refine(mesh, args.levels, options, "native")
osd = subdiv.refine(mesh, args.levels, options, "osd")
identical = all(np.array_equal(a.points, b.points) for a, b in zip(native.levels, osd.levels))
print("engines agree within 1e-6:", comparison.agrees(1e-6), "| arrays bit-identical:", identical)

# %% [markdown]
# ## Time both engines at every level
# The best of a few runs of the whole refinement (topology, positions,
# every level handed to numpy), with the GIL released inside.

# %%
levels = list(range(1, args.levels + 1))
timing: dict[str, list[float]] = {"native": [], "osd": []}
for level in levels:
    for engine in timing:
        best = float("inf")
        for _ in range(args.runs):
            start = time.perf_counter()
            subdiv.refine(mesh, level, options, engine)
            best = min(best, time.perf_counter() - start)
        timing[engine].append(best * 1e3)
    print(f"level {level}: native {timing['native'][-1]:.2f} ms, osd {timing['osd'][-1]:.2f} ms, "
          f"speed-up {timing['osd'][-1] / timing['native'][-1]:.2f}x")

# %% [markdown]
# ## Plot
# Left: the largest position deviation per level (a deviation of exactly 0
# is drawn at the floor and labelled). Right: the time per level.

# %%
import matplotlib  # noqa: E402  (only this example needs matplotlib)

if args.out:
    matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

floor = 1e-18
fig, (left, right) = plt.subplots(1, 2, figsize=(11, 4.2))
deviation = [max(row.max_position_deviation, floor) for row in comparison.levels]
bars = left.bar([row.level for row in comparison.levels], deviation, color="#4c72b0")
for bar, row in zip(bars, comparison.levels):
    label = "0 (identical)" if row.max_position_deviation == 0 else f"{row.max_position_deviation:.1e}"
    left.annotate(label, (bar.get_x() + bar.get_width() / 2, bar.get_height()), ha="center", va="bottom", fontsize=8)
left.set_yscale("log")
left.set_ylim(floor / 10, 1)
left.set_xlabel("level")
left.set_ylabel("max |native - osd| position")
left.set_title("deviation, native against OpenSubdiv")
right.plot(levels, timing["native"], "o-", label="native (Rust)")
right.plot(levels, timing["osd"], "s-", label=f"osd (OpenSubdiv {subdiv.OSD_VERSION})")
right.set_yscale("log")
right.set_xticks(levels)
right.set_xlabel("level")
right.set_ylabel("best time per refinement, ms")
right.set_title("timing")
right.legend()
fig.suptitle(name)
fig.tight_layout()
if args.out:
    fig.savefig(args.out, dpi=110)
    print("wrote", args.out)
else:
    plt.show()
