#!/usr/bin/env python3
"""Checks this project's performance targets against `subdiv bench` output.

usage: scripts/check-targets.py BENCH.json [BENCH.json ...]

`subdiv bench --out DIR` writes DIR/bench.json: measurements and ratios only.
The targets are this project's own (issue #6), so they are judged here, not
printed by the product:

- level-4 "topology + positions": OpenSubdiv's time / native time at least 3x
  on one thread and 5x on two or more, against OpenSubdiv's faster time
  (alone or interleaved: sharing the C allocator can slow it down);
- "stencil apply (f32)": at least 4x OpenSubdiv's EvalStencils;
- stencil apply at 50% or more of the memory bandwidth measured with the run's
  threads;
- the whole process, `subdiv refine torus.obj --level 4` as typed (every
  core), at least 3x faster than the C++ program against OpenSubdiv, with at
  most 0.6x its peak memory;
- the OBJ writer at 200 MB/s or more;
- issue #21: the OBJ reader at 1 GB/s or more on one thread, on the big inputs;
- issue #21, production meshes: on the inputs refined at most two levels
  (the grid, the production-like mesh with UVs), every in-process row at
  least 3x OpenSubdiv on one thread and 5x on two or more; their whole
  process at levels 1 and 2 (on the run's threads) at most 0.2x the C++
  program's time and 0.5x its peak memory;
- issue #23, adaptive refinement: every adaptive row ("adaptive topology
  (isolation N)", "adaptive positions (f32, isolation N)") at least 3x
  OpenSubdiv (the target is set for one thread; runs on more threads are
  judged against the same 3x);
- issue #24, the limit surface: the rows of the same section "patch table +
  PatchMap (isolation 3)" and "limit evaluation (N locations, ...)" at least
  3x OpenSubdiv likewise;
- issue #25, tessellation: every row of the tessellation section (the tori,
  Catmull-Clark and Loop, at rates 4 and 16, against OpenSubdiv's Bfr in one
  C++ loop) at least 3x
  OpenSubdiv on one thread.

Prints one line per target and exits 1 when any is not met (2 on bad input).
"""

import json
import sys


def judge(report):
    """Yields (description, value text, target text, met) for one report."""
    threads = report["threads"]
    alone = {(a["input"], a["scheme"], a["level"]): a["alone"] for a in report.get("osd_alone", [])}
    for r in report["rows"]:
        if r["task"] == "topology + positions" and r["level"] == 4:
            goal = 5.0 if threads >= 2 else 3.0
            a = alone.get((r["input"], r["scheme"], r["level"]))
            faster_alone = a is not None and a < r["osd"]
            speedup = (a if faster_alone else r["osd"]) / r["native"]
            note = ""
            if faster_alone:
                note = " against OpenSubdiv alone (%.1f ms; %.2fx interleaved)" % (
                    a * 1e3, r["osd"] / r["native"])
            yield ("level 4 topology + positions, %s %s, %d thread(s)" % (r["input"], r["scheme"], threads),
                   "%.2fx%s" % (speedup, note), "%gx" % goal, speedup >= goal)
    for r in report["rows"]:
        if r["task"] == "stencil apply (f32)":
            speedup = r["osd"] / r["native"]
            yield ("stencil apply (f32), %s %s" % (r["input"], r["scheme"]),
                   "%.2fx" % speedup, "4x", speedup >= 4.0)
    if report.get("stencil_bandwidth"):
        share = report["stencil_bandwidth"][0] / report["bandwidth"]
        yield ("stencil apply bandwidth, %d thread(s)" % threads,
               "%.0f%% of measured" % (100 * share), "50%", share >= 0.5)
    whole = report.get("whole_process") or []
    if isinstance(whole, dict):  # reports written before the big inputs had one
        whole = [whole]
    for w in whole:
        progs = {p["kind"]: p for p in w["programs"]}
        cpp = progs.get("cpp")
        if not cpp:
            continue
        peak = max(p["peak_bytes"] for k, p in progs.items() if k.startswith("native"))
        if w["level"] > 2:
            # Issue #6: the quad torus at level 4, as typed (every core).
            typed = progs.get("native-as-typed") or progs.get("native")
            ratio = cpp["seconds"] / typed["seconds"]
            yield ("whole process, `subdiv refine INPUT.obj --level %d` as typed (%d threads), %s" % (
                w["level"], w["cores"], w["input"]), "%.2fx" % ratio, "3x", ratio >= 3.0)
            if peak and cpp["peak_bytes"]:
                ratio = peak / cpp["peak_bytes"]
                yield ("peak memory native / C++ program, %s level %d" % (w["input"], w["level"]),
                       "%.2f" % ratio, "0.6", ratio <= 0.6)
        else:
            # Issue #21: the big inputs at levels 1 and 2, on the run's
            # threads: at most 0.2x the C++ program's time, 0.5x its memory.
            native = progs["native"]
            ratio = native["seconds"] / cpp["seconds"]
            yield ("whole process / C++ program, %s level %d, %d thread(s)" % (
                w["input"], w["level"], w["threads"]), "%.2f" % ratio, "0.2", ratio <= 0.2)
            if peak and cpp["peak_bytes"]:
                ratio = peak / cpp["peak_bytes"]
                yield ("peak memory native / C++ program, %s level %d" % (w["input"], w["level"]),
                       "%.2f" % ratio, "0.5", ratio <= 0.5)
    shallow = {r["input"] for r in report["rows"]} - {
        r["input"] for r in report["rows"] if r["level"] > 2}
    goal = 5.0 if threads >= 2 else 3.0
    for r in report["rows"]:
        if r["input"] in shallow:
            speedup = r["osd"] / r["native"]
            yield ("%s, %s %s level %d, %d thread(s)" % (
                r["task"], r["input"], r["scheme"], r["level"], threads),
                   "%.2fx" % speedup, "%gx" % goal, speedup >= goal)
    for a in report.get("adaptive", []):
        speedup = a["osd"] / a["native"]
        yield ("%s, %s %s (%d level(s) refined), %d thread(s)" % (
            a["task"], a["input"], a["scheme"], a["max_level"], threads),
               "%.2fx" % speedup, "3x", speedup >= 3.0)
    for t in report.get("tessellation", []):
        speedup = t["osd"] / t["native"]
        yield ("%s, %s %s, %d thread(s)" % (t["task"], t["input"], t["scheme"], threads),
               "%.2fx" % speedup, "3x", speedup >= 3.0)
    o = report.get("obj_writer")
    if o:
        rate = o["bytes"] / o["seconds"] / 1e6
        yield ("OBJ writer (%s, level %d)" % (o["input"], o["level"]),
               "%.0f MB/s" % rate, "200 MB/s", rate >= 200.0)
    for o in report.get("obj_reader", []):
        # Issue #21: OBJ text read at 1 GB/s on one thread (file read and parsed).
        rate = o["bytes"] / o["seconds_one_thread"] / 1e6
        yield ("OBJ reader on one thread, %s" % o["input"],
               "%.0f MB/s" % rate, "1000 MB/s", rate >= 1000.0)


def main(paths):
    if not paths:
        print(__doc__.strip().splitlines()[2], file=sys.stderr)
        return 2
    all_met = True
    for path in paths:
        try:
            with open(path, encoding="utf-8") as f:
                report = json.load(f)
        except (OSError, ValueError) as e:
            print("check-targets: %s: %s" % (path, e), file=sys.stderr)
            return 2
        print("%s (%s, %s):" % (path, report.get("date", "?"), report.get("machine", "?")))
        for what, value, target, met in judge(report):
            all_met &= met
            print("  %s: %s (target %s) %s" % (what, value, target, "met" if met else "NOT MET"))
    return 0 if all_met else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
