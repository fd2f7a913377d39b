#!/usr/bin/env python3
"""Cross-checks `subdiv curve --knots` against geomdl (NURBS-Python), an
independent NURBS implementation (issue #22, "Done when").

usage: scripts/check-nurbs.py SUBDIV [--cases N] [--seed S] [-v]

SUBDIV is the path of the `subdiv` binary. The script draws random curves
with a fixed seed: degrees 1 to 5, 2-D and 3-D, clamped and unclamped knot
vectors (interior knots repeated up to the degree), polynomial and rational
(weights in [0.2, 5]), and 1 to 4 insertions (random parameters inside the
domain, or existing interior knots again). For each curve it runs

    subdiv curve IN.txt --degree D --knots=... [--weights=...] --insert=T1,...
    subdiv curve IN.txt --degree D --knots=... [--weights=...] --samples N

and computes the same with geomdl: `operations.insert_knot` (Piegl and
Tiller's A5.1, on the weighted points of a `NURBS.Curve`) one knot at a time,
and `evaluate_single` at the N parameters spaced uniformly over the domain
[u_d, u_{m-d}], both ends included. geomdl's curves are made with
`normalize_kv=False`, so they keep the knot values (geomdl normalises to
[0, 1] by default) and accept unclamped vectors: its span search and basis
functions work on any non-decreasing vector, and so does its insertion for a
parameter inside the domain.

It compares the new knots (to the knot range), the new weights (to the
largest weight), the new control points and the samples (to the diagonal of
the input control polygon's bounding box), all to 1e-9 relative, and also
samples the CLI's inserted curve against geomdl's original one (insertion must
not change the shape).

Closed curves (`--closed`: the knots are the break points of one period) have
no counterpart in geomdl; they are checked by evaluation only: geomdl
evaluates the open curve over the periodic knots (the break points extended
by d knots on each side, the first d points repeated at the end), and the
CLI's samples before and after insertion must lie on it.

What geomdl does not cover: inserting a knot up to multiplicity d + 1
(geomdl refuses more than d), inserting at the ends of the domain (its span
search puts the right end in the last span, where A5.1's indices do not
apply), and evaluating at the domain's right end u_{m-d} when the knot
before it is equal (an unclamped vector ending its domain on a repeated
knot: geomdl picks the empty span there and divides by zero). The cases stay
inside the first two limits; for the third, that one sample is left out and
the summary says how often.

Prints a summary and exits 1 on any mismatch or failed run (2 on bad usage).
"""

import argparse
import math
import os
import random
import subprocess
import sys
import tempfile

try:
    from geomdl import BSpline, NURBS, operations
except ImportError:  # pragma: no cover - reported to the user
    sys.exit("check-nurbs: geomdl is not installed (pip install geomdl; `make test` does it in .venv)")

TOLERANCE = 1e-9


def number_list(values):
    """Comma-separated, each value exactly (repr round-trips a float)."""
    return ",".join(repr(float(x)) for x in values)


def random_knots(rng, degree, count, clamped):
    """`count + degree + 1` non-decreasing knots with a non-empty domain;
    interior knots repeated at most `degree` times."""
    m = count + degree  # index of the last knot
    knots = [rng.uniform(-5.0, 5.0)]
    run = 1
    for i in range(1, m + 1):
        repeat = run < degree and rng.random() < 0.2
        if clamped and (i <= degree or i >= m - degree + 1):
            repeat = True
        if clamped and i == m - degree:
            repeat = False  # the first of the last d + 1 equal knots
        if repeat:
            knots.append(knots[-1])
            run += 1
        else:
            knots.append(knots[-1] + rng.uniform(0.05, 2.0))
            run = 1
    # A non-empty domain [u_d, u_{m-d}]: widen its last span if needed.
    if knots[m - degree] <= knots[degree]:
        shift = 1.0
        for i in range(m - degree, m + 1):
            knots[i] += shift
    return knots


def multiplicity(knots, t):
    return sum(1 for u in knots if u == t)


def random_insertions(rng, degree, knots, count):
    """`count` parameters strictly inside the domain: existing interior knots
    (while their multiplicity stays at most d) or fresh values at least 1e-6
    from every knot (geomdl counts knots within 1e-7 as equal)."""
    knots = list(knots)
    m = len(knots) - 1
    a, b = knots[degree], knots[m - degree]
    ts = []
    while len(ts) < count:
        interior = [u for u in knots if a < u < b and multiplicity(knots, u) < degree]
        if interior and rng.random() < 0.35:
            t = rng.choice(interior)
        else:
            t = rng.uniform(a, b)
            if not a < t < b or any(abs(t - u) < 1e-6 for u in knots):
                continue
        ts.append(t)
        knots.append(t)
        knots.sort()
    return ts


def geomdl_curve(degree, points, knots, weights):
    if weights is None:
        curve = BSpline.Curve(normalize_kv=False)
        curve.degree = degree
        curve.ctrlpts = [list(p) for p in points]
    else:
        curve = NURBS.Curve(normalize_kv=False)
        curve.degree = degree
        curve.ctrlptsw = [[c * w for c in p] + [w] for p, w in zip(points, weights)]
    curve.knotvector = list(knots)
    return curve


def geomdl_state(curve):
    """(knots, Euclidean points, weights or None)."""
    if isinstance(curve, NURBS.Curve):
        pw = curve.ctrlptsw
        return (
            list(curve.knotvector),
            [[c / p[-1] for c in p[:-1]] for p in pw],
            [p[-1] for p in pw],
        )
    return list(curve.knotvector), [list(p) for p in curve.ctrlpts], None


def parameters(a, b, count):
    """As the CLI spaces them: a + (b - a) i / (N - 1), the last exactly b."""
    return [b if i == count - 1 else a + (b - a) * (i / (count - 1)) for i in range(count)]


class Runner:
    def __init__(self, binary, directory):
        self.binary = binary
        self.directory = directory
        self.runs = 0

    def curve(self, points, args):
        path = os.path.join(self.directory, "curve-%d.txt" % self.runs)
        self.runs += 1
        with open(path, "w") as f:
            f.write("".join(" ".join(repr(float(c)) for c in p) + "\n" for p in points))
        cmd = [self.binary, "curve", path] + args
        done = subprocess.run(cmd, capture_output=True, text=True)
        if done.returncode != 0:
            raise RuntimeError("%s: exit %d: %s" % (" ".join(cmd), done.returncode, done.stderr.strip()))
        return parse_output(done.stdout)


def parse_output(text):
    """(knots or None, weights or None, points) of a points file with headers."""
    knots = weights = None
    points = []
    for line in text.splitlines():
        if line.startswith("# knots "):
            knots = [float(x) for x in line[len("# knots ") :].split()]
        elif line.startswith("# weights "):
            weights = [float(x) for x in line[len("# weights ") :].split()]
        elif line.strip() and not line.startswith("#"):
            points.append([float(x) for x in line.split()])
    return knots, weights, points


def bbox_size(points):
    dim = len(points[0])
    lo = [min(p[i] for p in points) for i in range(dim)]
    hi = [max(p[i] for p in points) for i in range(dim)]
    return max(math.sqrt(sum((h - l) ** 2 for h, l in zip(hi, lo))), 1e-300)


def point_deviation(ours, theirs, size):
    """The largest distance between corresponding points, relative to size
    (infinite when the counts differ)."""
    if len(ours) != len(theirs):
        return math.inf
    worst = 0.0
    for p, q in zip(ours, theirs):
        if len(p) != len(q):
            return math.inf
        worst = max(worst, math.sqrt(sum((a - b) ** 2 for a, b in zip(p, q))) / size)
    return worst


def value_deviation(ours, theirs, scale):
    if ours is None or theirs is None:
        return 0.0 if ours is None and theirs is None else math.inf
    if len(ours) != len(theirs):
        return math.inf
    return max((abs(a - b) / scale for a, b in zip(ours, theirs)), default=0.0)


class Tally:
    """The largest deviation of each quantity, and where it occurred."""

    def __init__(self):
        self.worst = {}
        self.failures = []

    def add(self, what, deviation, case):
        old = self.worst.get(what, (-1.0, None))
        if deviation > old[0]:
            self.worst[what] = (deviation, case)
        if not deviation <= TOLERANCE:
            self.failures.append("%s: %s deviates by %.3g (relative)" % (case, what, deviation))


def describe(index, degree, clamped, weights, closed, dim):
    return "case %d (degree %d, %s, %s, %d-D)" % (
        index,
        degree,
        "closed" if closed else ("clamped" if clamped else "unclamped"),
        "rational" if weights is not None else "polynomial",
        dim,
    )


def check_open(rng, runner, tally, index, stats):
    degree = 1 + index % 5
    clamped = (index // 5) % 2 == 0
    rational = (index // 10) % 2 == 0
    dim = 2 + rng.randrange(2)
    count = degree + 1 + rng.randrange(6)
    points = [[rng.uniform(-10.0, 10.0) for _ in range(dim)] for _ in range(count)]
    weights = [rng.uniform(0.2, 5.0) for _ in range(count)] if rational else None
    knots = random_knots(rng, degree, count, clamped)
    inserts = random_insertions(rng, degree, knots, 1 + rng.randrange(4))
    case = describe(index, degree, clamped, weights, False, dim)
    stats["open"] += 1
    stats["insertions"] += len(inserts)
    stats["repeats"] += sum(1 for t in inserts if t in knots)

    base = ["--degree", str(degree), "--knots=" + number_list(knots)]
    if weights is not None:
        base.append("--weights=" + number_list(weights))
    size = bbox_size(points)

    # Insertion: the new knots, weights and control points.
    new_knots, new_weights, new_points = runner.curve(points, base + ["--insert=" + number_list(inserts)])
    reference = geomdl_curve(degree, points, knots, weights)
    for t in inserts:
        operations.insert_knot(reference, [t], [1])
    ref_knots, ref_points, ref_weights = geomdl_state(reference)
    tally.add("knots after insertion", value_deviation(new_knots, ref_knots, knots[-1] - knots[0]), case)
    if weights is not None:
        tally.add("weights after insertion", value_deviation(new_weights, ref_weights, max(weights)), case)
    elif new_weights is not None:
        tally.add("weights after insertion", math.inf, case)
    tally.add("control points after insertion", point_deviation(new_points, ref_points, size), case)

    # Sampling the given curve, and the CLI's inserted curve, against geomdl.
    n = 2 + rng.randrange(40)
    m = len(knots) - 1
    ts = parameters(knots[degree], knots[m - degree], n)
    # geomdl's span search puts the domain's right end u_{m-d} in the span
    # [u_{m-d-1}, u_{m-d}), empty when that knot is repeated (an unclamped
    # vector), and divides by zero there: leave that one sample out.
    keep = n
    if knots[m - degree - 1] == knots[m - degree]:
        keep = n - 1
        stats["right ends"] += 1
    original = geomdl_curve(degree, points, knots, weights)
    expected = [original.evaluate_single(t) for t in ts[:keep]]
    _, _, samples = runner.curve(points, base + ["--samples", str(n)])
    tally.add("samples", point_deviation(samples[:keep], expected, size), case)
    if len(samples) != n:
        tally.add("samples", math.inf, case)
    again = ["--degree", str(degree), "--knots=" + number_list(new_knots)]
    if new_weights is not None:
        again.append("--weights=" + number_list(new_weights))
    _, _, samples = runner.curve(new_points, again + ["--samples", str(n)])
    tally.add("samples after insertion", point_deviation(samples[:keep], expected, size), case)
    if len(samples) != n:
        tally.add("samples after insertion", math.inf, case)


def check_closed(rng, runner, tally, index, stats):
    """A closed curve, by evaluation only (geomdl has no periodic curves)."""
    degree = 1 + index % 5
    rational = index % 2 == 0
    dim = 2 + rng.randrange(2)
    count = max(degree, 2) + rng.randrange(5)  # distinct points
    points = [[rng.uniform(-10.0, 10.0) for _ in range(dim)] for _ in range(count)]
    weights = [rng.uniform(0.2, 5.0) for _ in range(count)] if rational else None
    breaks = [rng.uniform(-5.0, 5.0)]
    for _ in range(count):
        breaks.append(breaks[-1] + rng.uniform(0.1, 2.0))
    period = breaks[-1] - breaks[0]
    # The open curve over the periodic knots: d knots of the previous period
    # before s_0, d of the next after s_n, the first d points repeated.
    knots = [breaks[count - i] - period for i in range(degree, 0, -1)] + breaks
    knots += [breaks[i] + period for i in range(1, degree + 1)]
    wrapped = points + points[:degree]
    wrapped_w = weights + weights[:degree] if weights is not None else None
    inserts = [rng.uniform(breaks[0], breaks[-1]) for _ in range(1 + rng.randrange(4))]
    case = describe(index, degree, False, weights, True, dim)
    stats["closed"] += 1

    base = ["--closed", "--degree", str(degree), "--knots=" + number_list(breaks)]
    if weights is not None:
        base.append("--weights=" + number_list(weights))
    size = bbox_size(points)
    n = 2 + rng.randrange(40)
    ts = parameters(breaks[0], breaks[-1], n)
    reference = geomdl_curve(degree, wrapped, knots, wrapped_w)
    expected = [reference.evaluate_single(t) for t in ts]
    _, _, samples = runner.curve(points, base + ["--samples", str(n)])
    tally.add("closed: samples", point_deviation(samples, expected, size), case)
    new_breaks, new_weights, new_points = runner.curve(points, base + ["--insert=" + number_list(inserts)])
    again = ["--closed", "--degree", str(degree), "--knots=" + number_list(new_breaks)]
    if new_weights is not None:
        again.append("--weights=" + number_list(new_weights))
    _, _, samples = runner.curve(new_points, again + ["--samples", str(n)])
    tally.add("closed: samples after insertion", point_deviation(samples, expected, size), case)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("subdiv", help="path of the subdiv binary")
    parser.add_argument("--cases", type=int, default=200, help="open curves (default 200)")
    parser.add_argument("--seed", type=int, default=22, help="random seed (default 22)")
    parser.add_argument("-v", "--verbose", action="store_true", help="print every failure")
    args = parser.parse_args()
    if not os.access(args.subdiv, os.X_OK):
        print("check-nurbs: %s is not an executable" % args.subdiv, file=sys.stderr)
        return 2
    rng = random.Random(args.seed)
    tally = Tally()
    stats = {"open": 0, "closed": 0, "insertions": 0, "repeats": 0, "right ends": 0}
    errors = []
    with tempfile.TemporaryDirectory(prefix="check-nurbs-") as directory:
        runner = Runner(args.subdiv, directory)
        for index in range(args.cases):
            try:
                check_open(rng, runner, tally, index, stats)
            except Exception as e:  # a failed run or a geomdl refusal: reported
                errors.append("case %d: %s" % (index, e))
        for index in range(max(args.cases // 4, 1)):
            try:
                check_closed(rng, runner, tally, index, stats)
            except Exception as e:
                errors.append("closed case %d: %s" % (index, e))
        runs = runner.runs
    print(
        "check-nurbs: %d open curves (degrees 1-5, clamped and unclamped, polynomial and rational, "
        "%d insertions of which %d repeat a knot) and %d closed curves; %d runs of %s"
        % (stats["open"], stats["insertions"], stats["repeats"], stats["closed"], runs, args.subdiv)
    )
    if stats["right ends"]:
        print(
            "  %d curves end their domain on a repeated knot: geomdl cannot evaluate that end "
            "(an empty span), so their last sample is not compared" % stats["right ends"]
        )
    for what, (deviation, case) in sorted(tally.worst.items()):
        print("  %-32s max relative deviation %.3g  (%s)" % (what, deviation, case))
    shown = tally.failures if args.verbose else tally.failures[:10]
    for line in errors + shown:
        print("  FAIL " + line)
    if errors or tally.failures:
        print(
            "check-nurbs: %d failed runs, %d deviations over %g" % (len(errors), len(tally.failures), TOLERANCE)
        )
        return 1
    print("check-nurbs: all agree with geomdl within %g relative" % TOLERANCE)
    return 0


if __name__ == "__main__":
    sys.exit(main())
