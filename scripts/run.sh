#!/usr/bin/env bash
# Quick start, command 1: install what is missing, build the tool (only `pronk`: not the
# tests, the benchmarks or the Python module), run the default study (study 2: tune the
# legged robot to run at ~50 % duty cycle, 300 evaluations over 16 disturbed scenarios,
# validated on 64 held-out trials) into out/, and write its pages (the page templates are
# committed in web/dist: no Node needed).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/scripts/setup.sh"
PRONK_BUILD_TARGETS=pronk "$root/scripts/build.sh" "$root/build"
cd "$root"
out=out/study2_legged_pulse_duty50
rm -rf "$out"  # a fresh run (an existing journal would need --resume)
./build/pronk optimize studies/study2_legged_pulse_duty50.json --out "$out"
./build/pronk view "$out/tuned" -q  # the tuned design's run page
for page in "$out/report.html" "$out/tuned/view.html"; do
  [[ -s "$page" ]] || { echo "run.sh: $page was not written" >&2; exit 1; }
done
echo "summary:  $out/summary.md"
echo "figures:  $out/history.svg $out/compare.svg $out/tuned/motion.svg"
echo "pages:    $out/report.html (the study) $out/tuned/view.html (the tuned run): open them in a browser"
echo "design:   $out/design.json (check it: ./build/pronk reproduce $out/design.json)"
