#!/usr/bin/env python3
"""README's benchmark table from two `subdiv bench` outputs.

    scripts/bench-table.py docs/bench/threads1/bench.json docs/bench/threads2/bench.json

prints a Markdown table of the deepest level of every input (times from the
first run, speed-ups from both) followed by the parallel-use rows, the
adaptive rows (their level is the isolation level) and the tessellation
rows (level 0: the base faces, tessellated at the rate the task names). Nothing
is typed by hand: rerun `subdiv bench` into docs/bench/ and this script, and
paste its output into README.md's "Benchmarks" section.
"""
import json
import sys


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    one, two = (json.load(open(path)) for path in sys.argv[1:])
    key = lambda r: (r["input"], r["scheme"], r["level"], r["task"])
    extra = ("parallel", "adaptive", "tessellation")
    second = {key(r): r for r in two["rows"] + [r for k in extra for r in two.get(k, [])]}
    deepest = {}
    for r in one["rows"]:
        deepest[(r["input"], r["scheme"])] = max(deepest.get((r["input"], r["scheme"]), 0), r["level"])
    print(
        f"| input | scheme | level | task | native ms | OpenSubdiv ms "
        f"| speed-up, {one['threads']} thread(s) | speed-up, {two['threads']} thread(s) |"
    )
    print("| --- | --- | ---: | --- | ---: | ---: | ---: | ---: |")
    rows = [r for r in one["rows"] if r["level"] == deepest[(r["input"], r["scheme"])]]
    for r in rows + [r for k in extra for r in one.get(k, [])]:
        other = second.get(key(r))
        speedup2 = f"{other['osd'] / other['native']:.2f}x" if other else "-"
        print(
            f"| {r['input']} | {r['scheme']} | {r['level']} | {r['task']} "
            f"| {r['native'] * 1e3:.2f} | {r['osd'] * 1e3:.2f} "
            f"| {r['osd'] / r['native']:.2f}x | {speedup2} |"
        )


if __name__ == "__main__":
    main()
