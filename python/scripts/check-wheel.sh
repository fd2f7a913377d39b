#!/bin/bash
# Installs a built wheel into a fresh, temporary virtual environment (with
# numpy, nothing else) and runs the ten-line smoke script there, from outside
# the source tree so that only the installed package can be imported.
# Usage: python/scripts/check-wheel.sh WHEEL
set -euo pipefail
wheel=$(realpath "$1")
script=$(realpath "$(dirname "$0")/wheel_smoke.py")
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
python3 -m venv "$tmp/venv"
"$tmp/venv/bin/pip" install --quiet --disable-pip-version-check "$wheel" numpy==2.4.6
cd "$tmp" && "$tmp/venv/bin/python" "$script"
