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
