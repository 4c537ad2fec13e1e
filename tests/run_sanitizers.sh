#!/usr/bin/env bash
# ctest's "sanitizers" test: configures, builds and runs the unit tests with AddressSanitizer and
# UndefinedBehaviorSanitizer (CMakePresets.json "asan": gcc, -O1, -fno-omit-frame-pointer, every
# report fatal) in build-asan/. Incremental: a second run rebuilds only what changed.
# Leaks are reported; tests/lsan.supp silences those inside Mesa, LLVM, Embree and TBB only.
# Usage: bash tests/run_sanitizers.sh [GTEST_FILTER]
set -euo pipefail
cd "$(dirname "$0")/.."
start=$(date +%s)
if [ ! -f build-asan/build.ninja ]; then
  cmake --preset asan >/dev/null
fi
# Two jobs: ctest -j2 runs the rest of the suite beside this build.
cmake --build --preset asan --parallel 2
cc -shared -fPIC -O1 -o build-asan/libno_dlclose.so tests/no_dlclose.c
built=$(date +%s)
export LD_PRELOAD="$PWD/build-asan/libno_dlclose.so"
export ASAN_OPTIONS="halt_on_error=1:abort_on_error=1:detect_leaks=1:verify_asan_link_order=0"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1"
export LSAN_OPTIONS="suppressions=$PWD/tests/lsan.supp:print_suppressions=0"
filter=${1:-*}
build-asan/bin/irad_tests --gtest_filter="$filter" --gtest_brief=1
build-asan/bin/irad bench --quick --quiet -o build-asan/bench_quick >/dev/null
echo "sanitizers: build $((built - start)) s, tests $(($(date +%s) - built)) s"
