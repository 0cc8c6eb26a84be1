#!/usr/bin/env bash
# Designs every robot of the family (studies/scenes/family/*.json) with `pronk design` into
# results/family/<robot>/ and writes the table results/family/README.md
# (scripts/family_table.py). Options after the first argument go to every `pronk design`.
#   scripts/family.sh [PRONK] [DESIGN OPTIONS...]
# PRONK_FAMILY="tripod hexapod" designs only those; PRONK_FAMILY_OUT another results directory.
# Each robot is also designed tuned on its nominal robot only (--tune-nominal) into
# <results directory>_nominal/<robot>/, the table's last column; PRONK_FAMILY_NOMINAL=0 skips
# that.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
pronk=$(realpath "${1:-$root/build/pronk}")
shift $(( $# > 0 ? 1 : 0 ))
# Relative paths from the source tree: the summaries name them, and results are cloned.
cd "$root"
out=${PRONK_FAMILY_OUT:-results/family}
robots=${PRONK_FAMILY:-$(cd "$root/studies/scenes/family" && ls *.json | sed 's/\.json$//')}
mkdir -p "$out"
nominal=${out}_nominal
design() {  # design ROBOT DIR [OPTIONS...]
  local r=$1 dir=$2
  shift 2
  local resume=()
  [[ -f "$dir/study.json" ]] && resume=(--resume)
  "$pronk" design "studies/scenes/family/$r.json" --out "$dir" "${resume[@]}" "$@"
}
for r in $robots; do
  echo "== $r"
  design "$r" "$out/$r" "$@"
  if [[ "${PRONK_FAMILY_NOMINAL:-1}" != 0 ]]; then
    echo "== $r, tuned on the nominal robot only"
    design "$r" "$nominal/$r" --tune-nominal "$@"
  fi
done
python3 "$root/scripts/family_table.py" "$out" "$nominal" > "$out/README.md.tmp" && mv "$out/README.md.tmp" "$out/README.md"
cat "$out/README.md"
