#!/usr/bin/env bash
# Renders `subdiv report --quick` in headless Chromium and checks the page:
#   - the screenshot exists and is not blank (many distinct colours);
#   - the DOM (after parsing) has the summary table, the verdict, the inline
#     SVG plots and the pictures of the shapes, and no external resources.
#
# Usage: scripts/check-report-html.sh [KEEP_DIR]
#   KEEP_DIR (optional) receives report/, screenshot.png and dom.html.
# Installs Debian's chromium with apt-get when it is missing (as root, or with sudo).
set -euo pipefail

cd "$(dirname "$0")/.."
root=$(pwd)

fail() { echo "check-report-html: FAIL: $*" >&2; exit 1; }

chromium_bin=""
for c in chromium chromium-browser; do
  if command -v "$c" >/dev/null 2>&1; then chromium_bin=$(command -v "$c"); break; fi
done
if [ -z "$chromium_bin" ]; then
  echo "check-report-html: installing chromium (apt-get)"
  if [ "$(id -u)" -eq 0 ]; then SUDO=""; else SUDO="sudo"; fi
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq chromium >/dev/null
  chromium_bin=$(command -v chromium) || fail "chromium is not installed"
fi

if [ ! -x target/release/subdiv ] || [ -n "$(find src Cargo.toml build.rs cpp -newer target/release/subdiv -print -quit 2>/dev/null)" ]; then
  cargo build --release
fi

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
out="$work/report"
profile="$work/profile"
mkdir -p "$profile"

status=0
./target/release/subdiv report --quick --out "$out" >"$work/stdout.txt" || status=$?
[ "$status" -eq 0 ] || fail "subdiv report exited with $status: $(tail -5 "$work/stdout.txt")"
html="$out/report.html"
[ -s "$html" ] || fail "no $html"

# No external resources at all: not even a URL.
if grep -Eiq 'https?://|<script|<link|<img|@import|url\((["'\'']?)(https?:|//)' "$html"; then
  fail "report.html refers to something outside itself"
fi

flags=(--headless --no-sandbox --disable-gpu --disable-quic --no-first-run
  --disable-background-networking --disable-component-update --disable-sync
  --user-data-dir="$profile" --hide-scrollbars)

png="$work/screenshot.png"
timeout 120 "$chromium_bin" "${flags[@]}" --screenshot="$png" --window-size=1280,2000 "file://$html" \
  >"$work/chromium.log" 2>&1 || true
[ -s "$png" ] || fail "chromium wrote no screenshot (see $(tail -3 "$work/chromium.log"))"

# Not blank: a PNG of the right size whose pixels have many distinct colours.
python3 - "$png" <<'EOF' || fail "the screenshot looks blank"
import struct, sys, zlib
data = open(sys.argv[1], "rb").read()
assert data[:8] == b"\x89PNG\r\n\x1a\n", "not a PNG"
pos, idat, w, h, ctype = 8, b"", 0, 0, 0
while pos < len(data):
    n, kind = struct.unpack(">I4s", data[pos:pos + 8])
    body = data[pos + 8:pos + 8 + n]
    if kind == b"IHDR":
        w, h, depth, ctype = struct.unpack(">IIBB", body[:10])
        assert depth == 8, "unexpected bit depth"
    elif kind == b"IDAT":
        idat += body
    pos += 12 + n
bpp = {2: 3, 6: 4}.get(ctype)
assert bpp, f"unexpected colour type {ctype}"
raw = zlib.decompress(idat)
stride = w * bpp
prev = bytearray(stride)
colours, dark = set(), 0
for y in range(h):
    f = raw[y * (stride + 1)]
    line = bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
    for i in range(stride):
        a = line[i - bpp] if i >= bpp else 0
        b = prev[i]
        c = prev[i - bpp] if i >= bpp else 0
        if f == 1: line[i] = (line[i] + a) & 255
        elif f == 2: line[i] = (line[i] + b) & 255
        elif f == 3: line[i] = (line[i] + (a + b) // 2) & 255
        elif f == 4:
            p = a + b - c
            pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
            line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
    prev = line
    if y % 4 == 0:
        for x in range(0, w, 4):
            px = bytes(line[x * bpp:x * bpp + 3])
            colours.add(px)
            if sum(px) < 200:
                dark += 1
print(f"screenshot {w}x{h}: {len(colours)} distinct colours (sampled), {dark} dark samples")
assert w >= 1000 and h >= 1000, "too small"
assert len(colours) > 50, "too few colours"
assert dark > 200, "no text"
EOF

dom="$work/dom.html"
timeout 120 "$chromium_bin" "${flags[@]}" --dump-dom "file://$html" >"$dom" 2>>"$work/chromium.log" || true
[ -s "$dom" ] || fail "chromium --dump-dom printed nothing"

inputs=$(grep -c '<section id="input-' "$dom" || true)
svgs=$(grep -o '<svg' "$dom" | wc -l)
plots=$(grep -c 'deviation from OpenSubdiv (log scale)</title>' "$dom" || true)
times=$(grep -c 'refine + positions: median time</title>' "$dom" || true)
pictures=$(grep -c 'coloured by deviation</title>' "$dom" || true)
polygons=$(grep -o '<polygon' "$dom" | wc -l)
echo "DOM: $inputs inputs, $svgs inline SVGs ($plots deviation plots, $times time plots, $pictures pictures), $polygons polygons"
[ "$inputs" -ge 10 ] || fail "expected the embedded inputs' sections in the DOM"
[ "$plots" -eq "$inputs" ] || fail "a deviation plot is missing"
[ "$times" -eq "$inputs" ] || fail "a time plot is missing"
[ "$pictures" -eq "$inputs" ] || fail "a picture is missing"
[ "$polygons" -ge 1000 ] || fail "the pictures have (almost) no faces"
grep -q '<table class="summary">' "$dom" || fail "no summary table"
grep -q 'class="verdict pass"' "$dom" || fail "no passing verdict"
grep -q '0 (bit-identical)' "$dom" || fail "exact zeros are not labelled"

if [ $# -ge 1 ]; then
  mkdir -p "$1"
  rm -rf "$1/report"
  cp -r "$out" "$1/report"
  cp "$png" "$1/screenshot.png"
  cp "$dom" "$1/dom.html"
  echo "kept the report, screenshot and DOM in $1"
fi
echo "check-report-html: OK"
