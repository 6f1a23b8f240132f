#!/usr/bin/env bash
# make fuzz FUZZ_SECONDS=N: builds the libFuzzer targets (fuzz/, clang,
# AddressSanitizer and UndefinedBehaviorSanitizer) in $FUZZ_BUILD and runs
# each for N seconds; exits non-zero on any finding (a crash, a sanitizer
# report, an input over 60 s or 4 GiB). docs/security.md says more.
#   FUZZ_SECONDS  seconds a target (default 60)
#   FUZZ_TARGETS  which targets (default: gltf state cli image)
#   FUZZ_JOBS     targets run at once (default 1)
#   FUZZ_BUILD    build folder (default build-fuzz)
#   FUZZ_FORK=1   keep going after a finding (libFuzzer's -fork=1 with
#                 -ignore_crashes, -ignore_timeouts, -ignore_ooms): for long
#                 runs, which then collect every finding
# The corpus each run grows stays in $FUZZ_BUILD/corpus/TARGET for the next
# run; findings go to $FUZZ_BUILD/findings, and each run's log to
# $FUZZ_BUILD/logs/TARGET.log. A finding, once fixed, belongs in
# tests/data/fuzz/TARGET/ (tests/test_fuzz_regressions.cpp runs those).
set -euo pipefail
repo=$(cd "$(dirname "$0")/.." && pwd)
seconds=${FUZZ_SECONDS:-60}
targets=${FUZZ_TARGETS:-gltf state cli image}
jobs=${FUZZ_JOBS:-1}
build=${FUZZ_BUILD:-$repo/build-fuzz}
case "$build" in /*) ;; *) build=$repo/$build ;; esac

if [ ! -f "$build/CMakeCache.txt" ]; then
  cmake -S "$repo" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DCMAKE_C_COMPILER=clang-14 -DCMAKE_CXX_COMPILER=clang++-14 -DSTRATA_FUZZ=ON >/dev/null
fi
names=()
for t in $targets; do names+=("fuzz_$t"); done
cmake --build "$build" -j "$(nproc)" --target "${names[@]}"

# Seeds, a folder with a few files for uris to find, and the generated
# compressed and WebP glTF files of a normal build when there is one.
rm -rf "$build/seeds" "$build/root"
generated=()
for d in "$repo/build/tests/compressed" "$repo/build/tests/webp"; do [ -d "$d" ] && generated+=("$d"); done
python3 "$repo/fuzz/make_seeds.py" "$build/seeds" "${generated[@]}"
mkdir -p "$build/root" "$build/findings" "$build/logs"
cp "$repo/tests/data/textures/checker.png" "$build/root/texture.png"
head -c 4096 /dev/zero >"$build/root/buffer.bin"
export STRATA_FUZZ_ROOT="$build/root"
export ASAN_OPTIONS="${ASAN_OPTIONS:-abort_on_error=0:detect_leaks=1:allocator_may_return_null=1}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}"

run_target() {
  local t=$1 dict=()
  case $t in gltf | image) dict=(-dict="$repo/fuzz/gltf.dict") ;; cli) dict=(-dict="$repo/fuzz/cli.dict") ;; esac
  mkdir -p "$build/corpus/$t"
  rm -f "$build/findings/$t-"*
  # The regression inputs first: each must pass as it is.
  local regressions=("$repo/tests/data/fuzz/$t"/*)
  if [ -e "${regressions[0]}" ]; then
    "$build/fuzz/fuzz_$t" -rss_limit_mb=4096 -timeout=60 "${regressions[@]}" >"$build/logs/$t-regressions.log" 2>&1 ||
      { echo "fuzz $t: a regression input fails again ($build/logs/$t-regressions.log)"; return 1; }
  fi
  local status=0 fork=()
  [ "${FUZZ_FORK:-0}" = 1 ] && fork=(-fork=1 -ignore_crashes=1 -ignore_timeouts=1 -ignore_ooms=1)
  "$build/fuzz/fuzz_$t" "$build/corpus/$t" "$build/seeds/$t" "${dict[@]}" "${fork[@]}" -max_total_time="$seconds" \
    -rss_limit_mb=4096 -timeout=60 -max_len=1048576 -print_final_stats=1 \
    -artifact_prefix="$build/findings/$t-" >"$build/logs/$t.log" 2>&1 || status=$?
  # The figures of the run: executions, their rate, coverage, the corpus.
  local execs rate cov corpus
  execs=$(grep -oE 'stat::number_of_executed_units: *[0-9]+' "$build/logs/$t.log" | grep -oE '[0-9]+$' || true)
  rate=$(grep -oE 'stat::average_exec_per_sec: *[0-9]+' "$build/logs/$t.log" | grep -oE '[0-9]+$' || true)
  cov=$(grep -oE 'cov: [0-9]+ ft: [0-9]+' "$build/logs/$t.log" | tail -1 || true)
  # -fork=1 prints no final statistics: the last status line's instead.
  [ -n "$execs" ] || execs=$(grep -oE '^#[0-9]+' "$build/logs/$t.log" | tail -1 | tr -d '#' || true)
  [ -n "$rate" ] || rate=$(grep -oE 'exec/s:? [0-9]+' "$build/logs/$t.log" | tail -1 | grep -oE '[0-9]+$' || true)
  corpus=$(find "$build/corpus/$t" -type f | wc -l)
  # Kept going past a finding (FUZZ_FORK); a slow-unit file (over 10 s,
  # libFuzzer's note) is not one: -timeout is the limit.
  if [ "$status" -eq 0 ] && find "$build/findings" -name "$t-*" ! -name "$t-slow-unit-*" | grep -q .; then status=1; fi
  if [ "$status" -ne 0 ]; then
    echo "fuzz $t: FINDING (exit $status) after ${execs:-?} executions: $(grep -m1 -E 'ERROR|SUMMARY|runtime error|Timeout|out-of-memory|deadly signal' "$build/logs/$t.log" || true)"
    find "$build/findings" -name "$t-*" ! -name "$t-slow-unit-*" | sed 's/^/  input: /'
    return 1
  fi
  echo "fuzz $t: ${seconds} s, ${execs:-?} executions (${rate:-?}/s), ${cov:-cov ?}, corpus $corpus inputs, no finding"
}

failed=0
running=0
pids=()
for t in $targets; do
  run_target "$t" &
  pids+=($!)
  running=$((running + 1))
  if [ "$running" -ge "$jobs" ]; then
    wait -n || failed=1
    running=$((running - 1))
  fi
done
while [ "$running" -gt 0 ]; do
  wait -n || failed=1
  running=$((running - 1))
done
exit $failed
