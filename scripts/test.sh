#!/usr/bin/env bash
# Quick start, command 2: install what is missing, build, run every test.
#   scripts/test.sh            Release build + CTest (the whole suite)
#   PRONK_SANITIZE=1 ...       also the address/undefined sanitizer build + CTest
#   PRONK_FUZZ_SECONDS=60 ...  also build the libFuzzer target and fuzz the scene loader
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
fuzz=${PRONK_FUZZ_SECONDS:-0}
if [[ "$fuzz" != 0 ]]; then export PRONK_WITH_FUZZ=1; fi
"$root/scripts/setup.sh"
"$root/scripts/build.sh" "$root/build"
(cd "$root/build" && ctest --output-on-failure -j "$(nproc)")
if [[ "${PRONK_SANITIZE:-0}" == 1 ]]; then
  # Only the tool and its tests (benchmarks and peers are timed in Release, not sanitized),
  # line tables only (-g1: full -g makes the sanitized compile 3x slower), a unity build
  # (468 s instead of 559 s on 2 cores), and the [heavy] tests are left to the Release tree
  # (see CMakeLists.txt).
  PRONK_BUILD_TARGETS="pronk pronk_tests" "$root/scripts/build.sh" "$root/build-asan" -DCMAKE_BUILD_TYPE=None -DCMAKE_CXX_FLAGS="-O1 -g1" -DPRONK_SANITIZE=ON -DCMAKE_UNITY_BUILD=ON
  (cd "$root/build-asan" && ASAN_OPTIONS=detect_leaks=1 ctest --output-on-failure -j "$(nproc)")
fi
if [[ "$fuzz" != 0 ]]; then
  cmake -S "$root" -B "$root/build-fuzz" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DCMAKE_CXX_COMPILER=clang++-14 -DPRONK_BUILD_FUZZ=ON -DPRONK_BUILD_TESTS=OFF >/dev/null
  cmake --build "$root/build-fuzz" --target fuzz_scene -j "$(nproc)"
  corpus=$(mktemp -d)
  "$root/scripts/make_fuzz_corpus.sh" "$corpus"
  mkdir -p "$root/build-fuzz/artifacts"
  "$root/build-fuzz/fuzz_scene" -max_total_time="$fuzz" -max_len=8192 -print_final_stats=1 \
    -artifact_prefix="$root/build-fuzz/artifacts/" "$corpus" 2>&1 | tail -n 15
  echo "fuzz: no crash in ${fuzz} s"
fi
