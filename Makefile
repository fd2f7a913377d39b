# subdiv — the two set-up commands:
#   make run    install what is missing, build in release mode, run the main job:
#               `subdiv report` on the embedded set, into ./report/
#   make test   install what is missing, run the whole test suite
# Both install the system packages they need with apt-get (as root) when missing.

SHELL := /bin/bash
CARGO ?= cargo
APT_PACKAGES := libosd-dev libclang-dev clang g++ pkg-config

.PHONY: run test deps lint fmt check-no-osd clean

deps:
	@missing=""; \
	for p in $(APT_PACKAGES); do \
	  dpkg-query -W -f='$${Status}' $$p 2>/dev/null | grep -q "install ok installed" || missing="$$missing $$p"; \
	done; \
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
	$(CARGO) build --no-default-features
	$(CARGO) build --no-default-features --features cli
	$(CARGO) test --no-default-features --lib

lint: deps
	$(CARGO) fmt --check
	$(CARGO) clippy --all-targets --all-features -- -D warnings
	$(CARGO) clippy --all-targets --no-default-features -- -D warnings
	$(CARGO) clippy --all-targets --no-default-features --features cli -- -D warnings
	RUSTDOCFLAGS="-D warnings" $(CARGO) doc --no-deps --all-features
	RUSTDOCFLAGS="-D warnings" $(CARGO) doc --no-deps --no-default-features

fmt:
	$(CARGO) fmt

clean:
	$(CARGO) clean
