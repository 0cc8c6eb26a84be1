#!/usr/bin/env bash
# Regenerates the `pronk bench` section of docs/performance.md (between its marker
# comments) from the bench output in results/bench/, so the numbers are never typed by hand.
# (The README's headline table quotes a few of them; update it by hand after a new run.)
#   bash scripts/update_readme_perf.sh          # from the committed results/bench/bench.json
#   bash scripts/update_readme_perf.sh --check  # write nothing; exit 1 if the page is stale
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
if [[ "${1:-}" == "--check" ]]; then
  exec /usr/bin/python3 scripts/update_readme_perf.py --check results/bench docs/performance.md
fi
/usr/bin/python3 scripts/update_readme_perf.py results/bench docs/performance.md
