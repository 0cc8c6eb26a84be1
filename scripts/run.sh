#!/usr/bin/env bash
# Quick start, command 1: install what is missing, build, run the default study
# (study 2: tune the legged robot to run at ~50 % duty cycle, 300 evaluations
# over 16 disturbed scenarios, validated on 64 held-out trials) into out/.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/scripts/setup.sh"
"$root/scripts/build.sh" "$root/build"
cd "$root"
out=out/study2_legged_pulse_duty50
rm -rf "$out"  # a fresh run (an existing journal would need --resume)
./build/pronk optimize studies/study2_legged_pulse_duty50.json --out "$out"
echo "summary:  $out/summary.md"
echo "figures:  $out/history.svg $out/compare.svg $out/tuned/motion.svg"
echo "design:   $out/design.json (check it: ./build/pronk reproduce $out/design.json)"
