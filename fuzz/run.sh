#!/usr/bin/env bash
# Builds the fuzzer (CMakePresets.json "fuzz": clang-14, libFuzzer, ASan, UBSan), seeds it and
# runs it, then merges what it found into a minimised corpus.
#   bash fuzz/run.sh [SECONDS] [JOBS]   (default 600 s, 2 jobs)
# Working corpus: build-fuzz/corpus (kept between runs); crashes: build-fuzz/artifacts.
# The minimised corpus for the repository (replayed by tests/test_fuzz_corpus.cpp) is written to
# build-fuzz/corpus-min; to keep it: rm tests/fuzz_corpus/* && cp build-fuzz/corpus-min/* tests/fuzz_corpus/
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-600}
jobs=${2:-2}
cmake --preset fuzz >/dev/null
cmake --build --preset fuzz
python3 fuzz/make_seeds.py build-fuzz/seeds
mkdir -p build-fuzz/corpus build-fuzz/artifacts
fuzzer=build-fuzz/bin/gltf_loader_fuzzer
options=(-dict=fuzz/gltf.dict -max_len=16384 -timeout=10 -rss_limit_mb=2048
         -artifact_prefix=build-fuzz/artifacts/ -print_final_stats=1)
# Fork mode ($jobs child processes) stops at the first crash, leak, timeout or out-of-memory and
# leaves its input in build-fuzz/artifacts.
"$fuzzer" "${options[@]}" -max_total_time="$seconds" -fork="$jobs" -ignore_crashes=0 \
  -ignore_timeouts=0 -ignore_ooms=0 \
  build-fuzz/corpus build-fuzz/seeds tests/fuzz_corpus
# The minimised corpus keeps the seeds (as seed-NAME) and the regression inputs by name, then
# adds the inputs of at most 1 KB that cover more (about 300 KB in all; taking larger inputs too
# gains some coverage for megabytes).
rm -rf build-fuzz/corpus-min build-fuzz/small && mkdir -p build-fuzz/corpus-min build-fuzz/small
for f in build-fuzz/seeds/*; do cp "$f" "build-fuzz/corpus-min/seed-$(basename "$f")"; done
cp tests/fuzz_corpus/regression-* build-fuzz/corpus-min/
find build-fuzz/corpus tests/fuzz_corpus -type f -size -1025c -exec cp {} build-fuzz/small/ \;
"$fuzzer" "${options[@]}" -merge=1 build-fuzz/corpus-min build-fuzz/small
echo "fuzz: corpus $(ls build-fuzz/corpus | wc -l) files, minimised" \
  "$(ls build-fuzz/corpus-min | wc -l) files, $(du -sh --apparent-size build-fuzz/corpus-min | cut -f1)"
