# subdiv — the two set-up commands:
#   make run    install what is missing, build in release mode, run the main job:
#               `subdiv report` on the embedded set, into ./report/
#   make test   install what is missing, run the whole test suite, then cross-check
#               `subdiv curve --knots` against geomdl (NURBS-Python) in .venv, and
#               build the Python module (python/) and run its pytest suite there
# Both install the system packages they need with apt-get (as root) when missing.

SHELL := /bin/bash
CARGO ?= cargo
APT_PACKAGES := libosd-dev libclang-dev clang g++ pkg-config
# The Python environment of scripts/check-nurbs.py (geomdl is pure Python).
VENV := .venv
GEOMDL := geomdl==5.4.0
# The Python module (issue #27): built with maturin into a wheel, installed
# into .venv, tested with pytest; the wheel is also checked in a fresh venv.
PY_TOOLS := maturin==1.16.0 numpy==2.4.6 pytest==9.2.0
# Pixar's USD library (`pxr`), for python/tests/test_usd_pixar.py: stages
# written and read by Pixar's own code.
USD_CORE := usd-core==26.11
WHEELS := python/target/wheels

.PHONY: run test deps lint fmt check-no-osd check-nurbs check-examples check-python clean

deps:
	@missing=""; \
	for p in $(APT_PACKAGES); do \
	  dpkg-query -W -f='$${Status}' $$p 2>/dev/null | grep -q "install ok installed" || missing="$$missing $$p"; \
	done; \
	if ! command -v python3 >/dev/null 2>&1; then \
	  missing="$$missing python3 python3-venv"; \
	elif ! python3 -c 'import ensurepip, venv' >/dev/null 2>&1; then \
	  missing="$$missing python3-venv"; \
	fi; \
	if [ -n "$$missing" ]; then \
	  echo "installing:$$missing"; \
	  if [ "$$(id -u)" -eq 0 ]; then SUDO=""; else SUDO="sudo"; fi; \
	  $$SUDO apt-get update -qq && DEBIAN_FRONTEND=noninteractive $$SUDO apt-get install -y -qq $$missing; \
	fi

run: deps
	$(CARGO) build --release
	./target/release/subdiv report --out report

test: deps
	$(CARGO) test --all-features
	$(MAKE) --no-print-directory check-nurbs
	$(MAKE) --no-print-directory check-examples
	$(MAKE) --no-print-directory check-python
	$(CARGO) build --no-default-features
	$(CARGO) build --no-default-features --features cli
	$(CARGO) test --no-default-features --lib

# The ports of OpenSubdiv's bfr tutorials run (each asserts what it shows:
# every point equal to OpenSubdiv's Bfr within 1e-9, shared corners and
# edges continuous, the watertight mesh without cracks).
BFR_TUTORIALS = 1_1 1_2 1_3 2_1 2_2
check-examples: deps
	@for t in $(BFR_TUTORIALS); do \
	  $(CARGO) run --quiet --all-features --example bfr_tutorial_$$t || exit 1; \
	done

# `subdiv curve --knots` against geomdl on random curves (issue #22): .venv is
# made when missing and geomdl installed into it when missing (no network
# needed once it is there).
check-nurbs: deps $(VENV)/bin/pip
	@$(VENV)/bin/python -c 'import geomdl' 2>/dev/null || \
	  $(VENV)/bin/pip install --quiet --disable-pip-version-check '$(GEOMDL)'
	$(CARGO) build --all-features
	$(VENV)/bin/python scripts/check-nurbs.py target/debug/subdiv

# The Python module: one debug build of python/ (maturin, its own cargo
# workspace and target directory; a test build compiles in about 40% of a
# release build's time here) into a wheel; the wheel installed into
# .venv and its pytest suite run against the `subdiv` CLI (bit for bit); then
# the same wheel in a fresh temporary venv with numpy only, running a
# ten-line script (python/scripts/wheel_smoke.py). maturin, numpy and pytest
# are installed into .venv when missing, and so is usd-core.
check-python: deps $(VENV)/bin/pip
	@$(VENV)/bin/python -c 'import maturin, numpy, pytest' 2>/dev/null || \
	  $(VENV)/bin/pip install --quiet --disable-pip-version-check $(PY_TOOLS)
	@$(VENV)/bin/python -c 'import pxr' 2>/dev/null || \
	  $(VENV)/bin/pip install --quiet --disable-pip-version-check '$(USD_CORE)'
	$(CARGO) build --all-features
	rm -rf $(WHEELS)
	cd python && ../$(VENV)/bin/maturin build --quiet --auditwheel skip --interpreter ../$(VENV)/bin/python
	$(VENV)/bin/pip install --quiet --disable-pip-version-check --force-reinstall --no-deps $(WHEELS)/subdiv-*.whl
	cd python/tests && SUBDIV_CLI=$(CURDIR)/target/debug/subdiv ../../$(VENV)/bin/python -m pytest -q -p no:cacheprovider .
	python/scripts/check-wheel.sh $(WHEELS)/subdiv-*.whl

$(VENV)/bin/pip:
	python3 -m venv $(VENV) || { rm -rf $(VENV); echo "python3 -m venv failed"; exit 1; }

lint: deps $(VENV)/bin/pip
	$(CARGO) fmt --check
	$(CARGO) clippy --all-targets --all-features -- -D warnings
	$(CARGO) clippy --all-targets --no-default-features -- -D warnings
	$(CARGO) clippy --all-targets --no-default-features --features cli -- -D warnings
	RUSTDOCFLAGS="-D warnings" $(CARGO) doc --no-deps --all-features
	RUSTDOCFLAGS="-D warnings" $(CARGO) doc --no-deps --no-default-features
	cd python && $(CARGO) fmt --check
	cd python && $(CARGO) clippy --all-targets -- -D warnings
	@$(VENV)/bin/python -c 'import mypy, numpy' 2>/dev/null || \
	  $(VENV)/bin/pip install --quiet --disable-pip-version-check mypy==2.4.1 numpy==2.4.6
	cd python && ../$(VENV)/bin/mypy --strict subdiv

fmt:
	$(CARGO) fmt
	cd python && $(CARGO) fmt

clean:
	$(CARGO) clean
	cd python && $(CARGO) clean
