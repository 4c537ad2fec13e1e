#!/usr/bin/env bash
# ctest's "sanitizers" test: configures, builds and runs the unit tests with AddressSanitizer and
# UndefinedBehaviorSanitizer (CMakePresets.json "asan": clang 14, -O1, -fno-omit-frame-pointer,
# every report fatal) in build-asan/. Incremental: a second run rebuilds only what changed. The
# preset builds everything as unity builds (batches of 8 sources) with line tables only (-g1),
# the suite's own files at -O0 (tests/CMakeLists.txt): every source file is compiled with the
# sanitizers. The suite's batches compile in 75 s on 2 cores from scratch (116 s of CPU); gcc 12
# takes about 1.5x as long per file as clang 14.
# Leaks are reported; tests/lsan.supp silences those inside Mesa, LLVM, Embree and TBB only.
# Usage: bash tests/run_sanitizers.sh [GTEST_FILTER]
# Without a filter it leaves out the slowest tests (1.5 s and more in the Release build, or 15 s
# and more under the sanitizers): accuracy checks at large N, long CLI round trips, the shared
# scenes' renders, ten thousand ring frames, whose code paths shorter tests run too (the loader on
# the conformance files, the ring, the level of detail, kept shadow maps and the representatives'
# faces in smaller scenes). CI time is shared: keep this under about 10 minutes.
set -euo pipefail
cd "$(dirname "$0")/.."
start=$(date +%s)
# A build-asan/ configured with another compiler is configured anew.
cache=build-asan/CMakeCache.txt
if [ -f "$cache" ] && ! grep -q '^CMAKE_CXX_COMPILER:.*clang++-14' "$cache"; then
  rm -rf build-asan
fi
if [ ! -f build-asan/build.ninja ]; then
  cmake --preset asan >/dev/null
fi
# Two jobs: ctest -j2 runs the rest of the suite beside this build.
cmake --build --preset asan --parallel 2 --target irad_tests irad
cc -shared -fPIC -O1 -o build-asan/libno_dlclose.so tests/no_dlclose.c
built=$(date +%s)
export LD_PRELOAD="$PWD/build-asan/libno_dlclose.so"
export ASAN_OPTIONS="halt_on_error=1:abort_on_error=1:detect_leaks=1:verify_asan_link_order=0"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1"
export LSAN_OPTIONS="suppressions=$PWD/tests/lsan.supp:print_suppressions=0"
slow=(
  JitterEdges.AgainstThePathTracerOverThePixelFootprint
  JitterEdges.ReferenceModeK1
  JitterEdges.InterleavedK4
  Batched.SquareLightOverPlaneMatchesLambert
  Batched.CornellBoxMatchesThePerVplPasses
  Batched.MirrorBoxMatchesThePerVplPasses
  LightAllocation.PowerBeatsUniformAgainstThePathTracer
  ClampField.EstimatorsAgreeOnLocalClampDistances
  BiasCompensation.IntegratingSphere
  BiasCompensation.FurnaceBox
  ScreenCompensation.IntegratingSphere
  HardCases.FourMillionPathsInAClosedBox
  HardCases.TwoMillimetreWallLeaksTheSameInEveryModeAtAnyScale
  HardCases.RasterRendererServesAnotherViewAndSize
  HardCases.CornellBoxRendersTheSameAtAnyScale
  Gl.OsMesaAndEglGiveTheSameImage
  BadInput.CommandLineExitsWithOneLineAndWritesNothing
  Determinism.RasterIsBitIdentical
  Parts.LocalClampAndCompensationSplitWithTheFullWalksField
  Interrupt.PartialOfTheRtVplEstimator
  LightBudget.TheDefaultRenderAgainstThePathTracer
  LightBudget.RoundsAreTheMeanOfIndependentLightSets
  LightBudget.ShadowsOfRepresentatives
  SharedScenes.UnlitFilesRenderWithTheWhiteEnvironmentAndOneWarning
  Batched.KeptShadowMapsOfEveryPathMatchDrawingThemAnew
  ShadowLod.NoNewLeaksBetweenTwoSubdividedRooms
  ShadowLod.SimplifiedShadowsStayCloseToTheFullMeshes
  Ring.DriftAfterTenThousandFramesStaysBounded
  Specular.CornellMirrorMatchesPathTracer
  Specular.PathTracerMirrorMatchesLambert
  ShadowLod.TheFacesDrawFewerTrianglesWithLod
  ShadowOcclusion.WhatAWallHidesIsNotDrawnAndNoPixelChanges
  EdgePixels.TracedOnesHoldRtVplsValue
  Glossy.WhiteFurnaceRoughMetalPathTracer
  Glossy.PlaneUnderSquareLightPathTracer
  GlossyCornell.PathTracerAndRtVplAgreeInEveryChannelsMean
  GlossyCornell.WithAMirrorWallTooPathTracerAndRtVplAgree
  RasterGlossy.InterleavedKeepsTheMeans
  ShadowHelpers.TheSameImageAsTheRenderersOwnContext
  ShadowHelpers.TheSameImageWithMirroredVpls
)
default_filter="*-$(IFS=:; echo "${slow[*]}")"
filter=${1:-$default_filter}
# Two shards side by side: once the rest of the suite is done, both cores run this. Each shard
# has its own temporary folder (gtest's TempDir and std::filesystem's), so that the tests' fixed
# file names meet neither the other shard's nor those of the Release suite running beside it.
pids=()
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
for shard in 0 1; do
  mkdir -p "$scratch/$shard"
  TMPDIR="$scratch/$shard" TEST_TMPDIR="$scratch/$shard" GTEST_TOTAL_SHARDS=2 \
    GTEST_SHARD_INDEX=$shard build-asan/bin/irad_tests --gtest_filter="$filter" --gtest_brief=1 &
  pids+=($!)
done
status=0
for pid in "${pids[@]}"; do wait "$pid" || status=1; done
[ "$status" -eq 0 ] || { echo "sanitizers: a shard of irad_tests failed"; exit 1; }
build-asan/bin/irad bench --quick --quiet -o build-asan/bench_quick >/dev/null
echo "sanitizers: build $((built - start)) s, tests $(($(date +%s) - built)) s"
