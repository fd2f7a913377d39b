#!/usr/bin/env bash
# Runs one cargo-fuzz target of fuzz/ for a time budget.
#
# usage: scripts/fuzz.sh TARGET SECONDS [LIBFUZZER_ARGS...]
#        scripts/fuzz.sh --list
#   TARGET    obj_parser | mesh_refine | mesh_differential | adaptive_differential |
#             bfr_differential | limit_nonmanifold | curve | usd_reader
#   SECONDS   wall-clock budget (libFuzzer's -max_total_time)
#
# What works here (checked on Rust 1.95 stable, cargo-fuzz 0.13.2):
#
# * cargo-fuzz itself installs and runs on stable (`cargo install cargo-fuzz`).
#   It builds with `-Cpasses=sancov-module` and `-Cllvm-args=-sanitizer-coverage-*`,
#   which stable rustc accepts; only the sanitizers need nightly
#   (`-Zsanitizer=address`). libfuzzer-sys compiles libFuzzer itself with the
#   system C++ compiler.
# * So: with a nightly toolchain installed (`rustup run nightly rustc` works),
#   the target is built with AddressSanitizer (Rust code) and the C++ shim is
#   compiled with clang++ -fsanitize=address too (SUBDIV_ASAN=1, see build.rs),
#   so heap errors in the shim are caught as well (OpenSubdiv's own library is
#   Debian's uninstrumented build: only its malloc/free go through ASan).
#   Without nightly, the target is built on stable with `--sanitizer none`:
#   coverage-guided libFuzzer with Rust's own checks (bounds, overflow with
#   -Cdebug-assertions, every assert) - panics, aborts and time-outs are still
#   caught, silent memory errors in C++ are not (scripts/asan.sh covers the
#   bridge under ASan on stable).
# * Override with FUZZ_TOOLCHAIN=nightly|stable and FUZZ_SANITIZER=address|none.
#
# Inputs that take longer than FUZZ_TIMEOUT seconds (default 10) count as
# hangs; more than FUZZ_RSS_MB (default 4096) MiB as out-of-memory. With
# FUZZ_KEEP_GOING=1 libFuzzer runs in fork mode and keeps going after a
# crash (every crash is still saved).
#
# SUBDIV_FUZZ_SKIP_REPEATED=1 makes the OpenSubdiv checks skip meshes with a
# face that names a vertex twice (a family of OpenSubdiv assertion aborts),
# to look past them.
#
# Corpus: fuzz/corpus/TARGET (grows), seeded from fuzz/seeds/TARGET and, for
# obj_parser, tests/malformed/*.obj. Crashes, hangs and the run's log go to
# fuzz/artifacts/TARGET/. Reproduce a crash with
#   scripts/fuzz.sh TARGET 0 fuzz/artifacts/TARGET/crash-...
# (any file argument makes libFuzzer run just those inputs).
set -euo pipefail

here=$(cd "$(dirname "$0")/.." && pwd)
targets=(obj_parser mesh_refine mesh_differential adaptive_differential bfr_differential limit_nonmanifold curve usd_reader)
if [[ ${1:-} == --list ]]; then
  printf '%s\n' "${targets[@]}"
  exit 0
fi
target=${1:?usage: $0 TARGET SECONDS [LIBFUZZER_ARGS...] (targets: ${targets[*]})}
seconds=${2:?usage: $0 TARGET SECONDS [LIBFUZZER_ARGS...]}
shift 2
if [[ " ${targets[*]} " != *" $target "* ]]; then
  echo "fuzz.sh: unknown target '$target' (known: ${targets[*]})" >&2
  exit 2
fi

if ! cargo fuzz --version >/dev/null 2>&1; then
  echo "fuzz.sh: installing cargo-fuzz" >&2
  cargo install cargo-fuzz --locked
fi

toolchain=${FUZZ_TOOLCHAIN:-}
if [[ -z $toolchain ]]; then
  if rustup run nightly rustc --version >/dev/null 2>&1; then
    toolchain=nightly
  else
    toolchain=stable
  fi
fi
if [[ $toolchain == nightly ]]; then
  sanitizer=${FUZZ_SANITIZER:-address}
else
  sanitizer=${FUZZ_SANITIZER:-none}
fi
build=(cargo "+$toolchain" fuzz)
opts=(-O -s "$sanitizer" --target-dir "$here/fuzz/target/$toolchain-$sanitizer")
if [[ $sanitizer == address ]]; then
  # The shim with the same (LLVM) ASan ABI as Rust's runtime.
  export SUBDIV_ASAN=1 CXX=${CXX:-clang++}
  export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:detect_odr_violation=0}
fi

corpus=$here/fuzz/corpus/$target
artifacts=$here/fuzz/artifacts/$target
mkdir -p "$corpus" "$artifacts"
seeds=()
[[ -d $here/fuzz/seeds/$target ]] && seeds+=("$here/fuzz/seeds/$target")
if [[ $target == obj_parser ]] && compgen -G "$here/tests/malformed/*.obj" >/dev/null; then
  seeds+=("$here/tests/malformed")
fi

cd "$here"
"${build[@]}" build "${opts[@]}" "$target"

# Any existing file among the extra arguments: reproduce instead of fuzzing.
for arg in "$@"; do
  if [[ -f $arg ]]; then
    exec "${build[@]}" run "${opts[@]}" "$target" "$@" -- -timeout="${FUZZ_TIMEOUT:-10}"
  fi
done

log=$artifacts/run-$(date +%Y%m%d-%H%M%S).log
lf_args=(
  -max_total_time="$seconds"
  -timeout="${FUZZ_TIMEOUT:-10}"
  -rss_limit_mb="${FUZZ_RSS_MB:-4096}"
  -max_len="${FUZZ_MAX_LEN:-8192}"
  -artifact_prefix="$artifacts/"
  -print_final_stats=1
)
if [[ ${FUZZ_KEEP_GOING:-0} == 1 ]]; then
  lf_args+=(-fork=1 -ignore_crashes=1 -ignore_timeouts=1 -ignore_ooms=1)
fi
echo "fuzz.sh: $target for ${seconds}s ($toolchain, sanitizer $sanitizer); log $log" >&2
start=$(date +%s)
set +e
"${build[@]}" run "${opts[@]}" "$target" "$corpus" "${seeds[@]}" -- "${lf_args[@]}" "$@" >"$log" 2>&1
status=$?
set -e
elapsed=$(( $(date +%s) - start ))

execs=$(grep -Eo 'stat::number_of_executed_units: *[0-9]+' "$log" | grep -Eo '[0-9]+$' | tail -1 || true)
if [[ -z $execs ]]; then
  # Fork mode prints no final stats: take the last status line's count.
  execs=$(grep -Eo '^#[0-9]+' "$log" | tr -d '#' | tail -1 || true)
fi
crashes=$(grep -Eo "(crash|timeout|oom|leak|slow-unit)-[0-9a-f]+" "$log" | sort -u || true)
echo "fuzz.sh: $target: exit $status after ${elapsed}s, ${execs:-?} executions, corpus $(find "$corpus" -type f | wc -l) inputs"
if [[ -n $crashes ]]; then
  echo "fuzz.sh: $target: found:"
  for c in $crashes; do echo "  $artifacts/$c"; done
  grep -E "panicked at|ERROR: (AddressSanitizer|libFuzzer)|SUMMARY" "$log" | sort | uniq -c | head -20
fi
exit "$status"
