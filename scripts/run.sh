#!/usr/bin/env bash
# Quick start, command 1: install what is missing, build, run the default job
# (the seed's legged running scene, pulse model) and write its outputs to out/.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/scripts/setup.sh"
"$root/scripts/build.sh" "$root/build"
cd "$root"
./build/pronk simulate studies/scenes/case3_legged_pulse.json --out out/case3_legged_pulse
