#!/usr/bin/env bash
# make test-sanitize: strata, its OpenImageIO module and the tests built with
# AddressSanitizer and UndefinedBehaviorSanitizer (STRATA_SANITIZE, gcc) in
# $SANITIZE_BUILD, then the whole suite on lavapipe, validation layers on as
# in `make test`. A sanitizer report in strata's code fails the test that
# ran it: ASan and UBSan stop the process (UBSan's -fno-sanitize-recover),
# LeakSanitizer makes its exit status non-zero. Leaks inside the Vulkan
# loader, driver and layers are suppressed (tests/sanitize/lsan.supp), no
# other. docs/testing.md says more.
#   SANITIZE_BUILD  build folder (default build-sanitize)
#   CTEST_ARGS      more ctest arguments (e.g. "-L unit")
set -euo pipefail
repo=$(cd "$(dirname "$0")/.." && pwd)
build=${SANITIZE_BUILD:-$repo/build-sanitize}
case "$build" in /*) ;; *) build=$repo/$build ;; esac
if [ ! -f "$build/CMakeCache.txt" ]; then
  cmake -S "$repo" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DSTRATA_SANITIZE=ON >/dev/null
fi
cmake --build "$build" -j "$(nproc)"
export ASAN_OPTIONS="detect_leaks=1"
export LSAN_OPTIONS="suppressions=$repo/tests/sanitize/lsan.supp:print_suppressions=0"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
cd "$build"
# LeakSanitizer itself crashes at the exit of some test processes ("Tracer
# caught signal 11" on a dynamic-TLS range of 0x21c2-0x10000032c4 in the
# main thread: Debian 12's gcc 12 runtime with glibc 2.36), after the test
# passed: always for the resumed state, at times for converge's report
# (seen once in two runs, 2026-12-06, after every check of the test had
# passed). Those tests run with leak detection off, ASan and UBSan still on.
no_leaks='state: a render resumed from its state, also one stopped by SIGINT|reference stores per-pixel variance, compare measures against it, converge reports'
status=0
# shellcheck disable=SC2086
if ctest -N -R "$no_leaks" ${CTEST_ARGS:-} | grep -q 'Total Tests: [1-9]'; then
  ASAN_OPTIONS=detect_leaks=0 ctest --output-on-failure -j 1 -R "$no_leaks" ${CTEST_ARGS:-} || status=$?
fi
# shellcheck disable=SC2086
ctest --output-on-failure -j 1 -E "$no_leaks" ${CTEST_ARGS:-} || status=$?
exit $status
