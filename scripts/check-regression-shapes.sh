#!/usr/bin/env bash
# Compares `subdiv refine` (both engines) with the independent OpenSubdiv
# driver (cpp/osd_driver.cpp) on OpenSubdiv's own regression
# shapes, level by level, byte for byte.
#
# usage: scripts/check-regression-shapes.sh OPENSUBDIV_CHECKOUT [LEVELS] [adaptive]
#   OPENSUBDIV_CHECKOUT  a checkout of OpenSubdiv (its regression/shapes/*.h
#                        hold the shapes as OBJ text in C++ string literals)
#   LEVELS               levels to check, default "1 2 3"
#   adaptive             refine with RefineAdaptive to each LEVEL instead
#                        (`subdiv refine --adaptive N --levels-json` against
#                        the driver's JSON: counts and faces exactly,
#                        positions within 1e-9 of the bounding-box diagonal)
#   bfr                  the Bfr way instead (LEVELS ignored): `subdiv eval
#                        --surface bfr --derivatives` at 20 pseudo-random
#                        locations per face (chosen by the driver) against the
#                        driver's Bfr (positions within 1e-9 of the
#                        bounding-box diagonal, derivatives within 1e-7), and
#                        `subdiv tessellate` at rates 1, 3 and 8 and 3 with
#                        --quads against the driver's tessellation (shared
#                        points evaluated by the first face using them, as
#                        bfr tutorial 2_2 does: the same facet count, the
#                        same set of points within 1e-9);
#                        a shape the OpenSubdiv engine refuses (a Bfr fault of
#                        3.5.0, docs/CONFORMANCE.md) is reported and skipped
# Nothing is downloaded; the shapes are read from the checkout you give.
set -euo pipefail
osd_src=${1:?usage: $0 OPENSUBDIV_CHECKOUT [LEVELS]}
levels=${2:-1 2 3}
mode=${3:-uniform}
here=$(cd "$(dirname "$0")/.." && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

cargo build --release --quiet --manifest-path "$here/Cargo.toml"
bin="$here/target/release/subdiv"
g++ -std=c++14 -O2 "$here/cpp/osd_driver.cpp" -losdCPU -o "$work/driver"

pass=0 fail=0
for header in "$osd_src"/regression/shapes/{catmark,bilinear,loop}_*.h; do
  name=$(basename "$header" .h)
  scheme=${name%%_*}
  python3 - "$header" "$work/$name.obj" <<'PY'
import ast, re, sys
text = open(sys.argv[1]).read()
parts = re.findall(r'^\s*"(.*)"\s*$', text, re.M)
open(sys.argv[2], "w").write("".join(ast.literal_eval('"' + p + '"') for p in parts))
PY
  if [ "$mode" = bfr ]; then
    if ! "$bin" tessellate "$work/$name.obj" --scheme "$scheme" --engine osd --rate 1 -o "$work/probe.obj" 2>"$work/probe.err"; then
      echo "refused by the OpenSubdiv engine: $name ($(tail -c 160 "$work/probe.err"))"
      continue
    fi
    "$work/driver" "$work/$name.obj" "$work/ref.txt" --bfr-eval "$work/at.txt" --bfr-random 20 --scheme "$scheme" 2>/dev/null || { echo "driver refused $name"; continue; }
    for engine in native osd; do
      if "$bin" eval "$work/$name.obj" --surface bfr --derivatives --at "$work/at.txt" -o "$work/out.txt" --scheme "$scheme" --engine "$engine" 2>/dev/null \
         && python3 - "$work/$name.obj" "$work/ref.txt" "$work/out.txt" <<'PY'
import math, sys
pts = [list(map(float, l.split()[1:4])) for l in open(sys.argv[1]) if l.startswith("v ")]
diag = max(math.dist([min(p[i] for p in pts) for i in range(3)], [max(p[i] for p in pts) for i in range(3)]), 1.0)
a, b = ([list(map(float, l.split())) for l in open(p)] for p in sys.argv[2:4])
assert len(a) == len(b) and len(a) > 0, "rows"
for ra, rb in zip(a, b):
    for k, (x, y) in enumerate(zip(ra, rb)):
        assert abs(x - y) <= (1e-9 if k < 3 else 1e-7) * diag, (k, x, y)
PY
      then
        pass=$((pass + 1))
      else
        fail=$((fail + 1)); echo "DIFFERENT: $name bfr eval ($engine)"
      fi
    done
    for tess in "1 no" "3 no" "8 no" "3 yes"; do
      set -- $tess
      "$work/driver" "$work/$name.obj" "$work/ref.obj" --bfr-tessellate "$1" --bfr-quads "$2" --scheme "$scheme" 2>/dev/null || { echo "driver refused $name"; continue; }
      quads=(); [ "$2" = yes ] && quads=(--quads)
      for engine in native osd; do
        if "$bin" tessellate "$work/$name.obj" --rate "$1" "${quads[@]}" -o "$work/out.obj" --scheme "$scheme" --engine "$engine" 2>/dev/null \
           && python3 - "$work/$name.obj" "$work/ref.obj" "$work/out.obj" <<'PY'
import bisect, math, sys
def read(path):
    v, f = [], 0
    for l in open(path):
        if l.startswith("v "): v.append(tuple(map(float, l.split()[1:4])))
        elif l.startswith("f "): f += 1
        elif l.startswith("# facets "): f = int(l.split()[2])
    return v, f
base, _ = read(sys.argv[1])
diag = max(math.dist([min(p[i] for p in base) for i in range(3)], [max(p[i] for p in base) for i in range(3)]), 1.0)
(a, fa), (b, fb) = read(sys.argv[2]), read(sys.argv[3])
assert fa == fb, ("facets", fa, fb)
tol = 1e-9 * diag
def covered(xs, ys):
    ys = sorted(ys); keys = [y[0] for y in ys]
    for p in xs:
        i = bisect.bisect_left(keys, p[0] - tol)
        while i < len(ys) and ys[i][0] <= p[0] + tol:
            if all(abs(s - t) <= tol for s, t in zip(p, ys[i])): break
            i += 1
        else:
            return p
assert covered(a, b) is None and covered(b, a) is None, "points"
PY
        then
          pass=$((pass + 1))
        else
          fail=$((fail + 1)); echo "DIFFERENT: $name tessellate rate $1 quads $2 ($engine)"
        fi
      done
    done
    continue
  fi
  for level in $levels; do
    if [ "$mode" = adaptive ]; then
      "$work/driver" "$work/$name.obj" "$work/ref.json" --adaptive "$level" --scheme "$scheme" 2>/dev/null || { echo "driver refused $name"; continue; }
      for engine in native osd; do
        if "$bin" refine "$work/$name.obj" --adaptive "$level" --levels-json "$work/out.json" --scheme "$scheme" --engine "$engine" 2>/dev/null \
           && python3 - "$work/ref.json" "$work/out.json" <<'PY'
import json, math, sys
a, b = (json.load(open(p))["levels"] for p in sys.argv[1:3])
assert len(a) == len(b), "number of levels"
pts = a[0]["positions"]
diag = math.dist([min(p[i] for p in pts) for i in range(3)], [max(p[i] for p in pts) for i in range(3)])
for la, lb in zip(a, b):
    for k in ("vertices", "edges", "faces", "face_vertices"):
        assert la[k] == lb[k], k
    assert all(math.dist(p, q) <= 1e-9 * max(diag, 1.0) for p, q in zip(la["positions"], lb["positions"]))
PY
        then
          pass=$((pass + 1))
        else
          fail=$((fail + 1)); echo "DIFFERENT: $name adaptive $level ($engine)"
        fi
      done
      continue
    fi
    "$work/driver" "$work/$name.obj" "$work/ref.obj" --level "$level" --scheme "$scheme" 2>/dev/null || { echo "driver refused $name"; continue; }
    for engine in native osd; do
      if "$bin" refine "$work/$name.obj" -o "$work/out.obj" --level "$level" --scheme "$scheme" --engine "$engine" 2>/dev/null \
         && cmp -s "$work/ref.obj" "$work/out.obj"; then
        pass=$((pass + 1))
      else
        fail=$((fail + 1)); echo "DIFFERENT: $name level $level ($engine)"
      fi
    done
  done
done
echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
