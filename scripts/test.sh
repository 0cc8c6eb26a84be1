#!/usr/bin/env bash
# Quick start, command 2: install what is missing, build, run every test.
#   scripts/test.sh            Release build + CTest (the whole suite)
#   PRONK_SANITIZE=1 ...       also the address/undefined sanitizer build + CTest
#   PRONK_FUZZ_SECONDS=60 ...  also build the libFuzzer targets and fuzz every loader and the
#                              journal reader (the seconds split evenly among them)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
fuzz=${PRONK_FUZZ_SECONDS:-0}
if [[ "$fuzz" != 0 ]]; then export PRONK_WITH_FUZZ=1; fi
# Node, npm, Chromium and the pinned npm packages for the browser test of the pages.
export PRONK_WITH_WEB=${PRONK_WITH_WEB:-1}
"$root/scripts/setup.sh"
"$root/scripts/build.sh" "$root/build"
(cd "$root/build" && ctest --output-on-failure -j "$(nproc)")
if [[ "${PRONK_SANITIZE:-0}" == 1 ]]; then
  # Only the tool and its tests (benchmarks and peers are timed in Release, not sanitized),
  # line tables only (-g1: full -g makes the sanitized compile 3x slower), the library in a
  # unity build (the tests compile file by file, see CMakeLists.txt), and the [heavy] tests
  # are left to the Release tree
  # (see CMakeLists.txt).
  PRONK_BUILD_TARGETS="pronk pronk_tests" "$root/scripts/build.sh" "$root/build-asan" -DCMAKE_BUILD_TYPE=None -DCMAKE_CXX_FLAGS="-O1 -g1" -DPRONK_SANITIZE=ON -DCMAKE_UNITY_BUILD=ON
  (cd "$root/build-asan" && ASAN_OPTIONS=detect_leaks=1 ctest --output-on-failure -j "$(nproc)")
fi
if [[ "$fuzz" != 0 ]]; then
  # One libFuzzer target per loader (scene, mechanism, study, map study) and the journal
  # reader; each fuzzes for its share of PRONK_FUZZ_SECONDS.
  targets=(scene mechanism study map_study journal)
  share=$(( fuzz / ${#targets[@]} > 0 ? fuzz / ${#targets[@]} : 1 ))
  # Unity build, -O1, line tables only, as the sanitizer tree: the fuzz targets link the
  # instrumented library, and this keeps its compile time down.
  cmake -S "$root" -B "$root/build-fuzz" -DCMAKE_BUILD_TYPE=None -DCMAKE_CXX_FLAGS="-O1 -g1" \
    -DCMAKE_UNITY_BUILD=ON \
    -DCMAKE_CXX_COMPILER=clang++-14 -DPRONK_BUILD_FUZZ=ON -DPRONK_BUILD_TESTS=OFF >/dev/null
  cmake --build "$root/build-fuzz" -j "$(nproc)" $(printf -- '--target fuzz_%s ' "${targets[@]}")
  mkdir -p "$root/build-fuzz/artifacts"
  for t in "${targets[@]}"; do
    corpus=$(mktemp -d)
    "$root/scripts/make_fuzz_corpus.sh" "$corpus" "$t"
    echo "fuzz_$t: ${share} s"
    "$root/build-fuzz/fuzz_$t" -max_total_time="$share" -max_len=8192 -print_final_stats=1 \
      -artifact_prefix="$root/build-fuzz/artifacts/fuzz_${t}_" "$corpus" 2>&1 | tail -n 15
    rm -rf "$corpus"
  done
  echo "fuzz: no crash in ${fuzz} s (${#targets[@]} targets, ${share} s each)"
fi
