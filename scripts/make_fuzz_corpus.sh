#!/usr/bin/env bash
# Builds the fuzzer's seed corpus from the shipped scenes: each scene once
# without and once with a --set line.
set -euo pipefail
out=${1:?corpus dir}
mkdir -p "$out"
i=0
for f in "$(dirname "$0")"/../studies/scenes/*.json; do
  { echo ""; cat "$f"; } > "$out/scene_$i"
  { echo "/controller/hop_height=0.3"; cat "$f"; } > "$out/set_$i"
  i=$((i + 1))
done
