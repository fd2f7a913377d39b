#!/usr/bin/env bash
# Compares `subdiv refine` (both engines) with the independent OpenSubdiv
# driver (cpp/osd_driver.cpp) on OpenSubdiv's own regression
# shapes, level by level, byte for byte.
#
# usage: scripts/check-regression-shapes.sh OPENSUBDIV_CHECKOUT [LEVELS]
#   OPENSUBDIV_CHECKOUT  a checkout of OpenSubdiv (its regression/shapes/*.h
#                        hold the shapes as OBJ text in C++ string literals)
#   LEVELS               levels to check, default "1 2 3"
# Nothing is downloaded; the shapes are read from the checkout you give.
set -euo pipefail
osd_src=${1:?usage: $0 OPENSUBDIV_CHECKOUT [LEVELS]}
levels=${2:-1 2 3}
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
