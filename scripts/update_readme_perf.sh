#!/usr/bin/env bash
# Regenerates the README's `pronk bench` section (between its marker comments)
# from the bench output in results/bench/, so the numbers are never typed by hand.
#   bash scripts/update_readme_perf.sh          # from the committed results/bench/bench.json
#   bash scripts/update_readme_perf.sh --run    # build (with the peers, when installed), run
#                                               # `pronk bench` into results/bench/, then update
# Uses Debian's /usr/bin/python3 (standard library only).
set -euo pipefail
cd "$(dirname "$0")/.."
if [[ "${1:-}" == "--run" ]]; then
  cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
  cmake --build build -j"$(nproc)" --target pronk $(
    for t in pronk_peer_cvode pronk_peer_mujoco; do
      cmake --build build --target help | grep -qw "$t" && echo "$t"
    done) >/dev/null
  build/pronk bench --out results/bench
fi
/usr/bin/python3 scripts/update_readme_perf.py results/bench README.md
