#!/usr/bin/env bash
# Designs every robot of the family (studies/scenes/family/*.json) with `pronk design` into
# results/family/<robot>/ and writes the table results/family/README.md
# (scripts/family_table.py). Options after the first argument go to every `pronk design`.
#   scripts/family.sh [PRONK] [DESIGN OPTIONS...]
# PRONK_FAMILY="tripod hexapod" designs only those; PRONK_FAMILY_OUT another results directory.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
pronk=$(realpath "${1:-$root/build/pronk}")
shift $(( $# > 0 ? 1 : 0 ))
# Relative paths from the source tree: the summaries name them, and results are cloned.
cd "$root"
out=${PRONK_FAMILY_OUT:-results/family}
robots=${PRONK_FAMILY:-$(cd "$root/studies/scenes/family" && ls *.json | sed 's/\.json$//')}
mkdir -p "$out"
for r in $robots; do
  echo "== $r"
  resume=()
  [[ -f "$out/$r/study.json" ]] && resume=(--resume)
  "$pronk" design "studies/scenes/family/$r.json" --out "$out/$r" "${resume[@]}" "$@"
done
python3 "$root/scripts/family_table.py" "$out" > "$out/README.md.tmp" && mv "$out/README.md.tmp" "$out/README.md"
cat "$out/README.md"
