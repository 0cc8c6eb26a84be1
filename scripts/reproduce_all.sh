#!/usr/bin/env bash
# Reproduces every committed design, each results/**/design.json (the stage designs of staged
# studies too; a last stage's through the staged design that carries it), with
# `pronk reproduce`, several at once, and fails when one does not reproduce.
#   scripts/reproduce_all.sh [PRONK [REPRODUCE OPTIONS...]]
# PRONK defaults to build/pronk. CTest runs the same reproductions one test per design
# (`reproduce/<path>`, label `reproduce`; so `bash scripts/test.sh` and CI do); this script
# runs them outside CTest, e.g.
#   scripts/reproduce_all.sh build/pronk --strict
# --strict: on the compiler and flags that recorded the designs, every value bit-identical
# whatever the commit, so a change that moves a number must re-record the designs it moves.
# Elsewhere the designs' own tolerances apply (docs/studies.md, "Reproducing on another
# machine"). PRONK_REPRODUCE_JOBS designs run at once (default: the core count), one thread
# each; PRONK_REPRODUCE_RESULTS names another results directory.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
pronk=$(realpath "${1:-$root/build/pronk}")
shift $(( $# > 0 ? 1 : 0 ))
results=${PRONK_REPRODUCE_RESULTS:-$root/results}
jobs=${PRONK_REPRODUCE_JOBS:-$(nproc)}
logs=$(mktemp -d)
trap 'rm -rf "$logs"' EXIT

mapfile -t all_designs < <(cd "$results" && find . -name design.json | sed 's|^\./||' | sort)
# A staged design carries its last stage's record, and reproducing it checks the last stage's
# own design.json against it: that file is reproduced once, through the staged design (the
# rule CMakeLists.txt applies to the CTest tests; "directory" is a key of the stage records only).
last_stage() {  # the last stage's design.json of staged design $1, if it is one
  { grep -o '"directory": *"[^"]*"' "$results/$1" || true; } | tail -n 1 |
    sed -E 's|.*"([^"]*)"$|\1|; s|.*/||; s|^|'"$(dirname "$1")"'/stages/|; s|$|/design.json|'
}
declare -A covered=()
for d in "${all_designs[@]}"; do
  s=$(last_stage "$d")
  if [[ -n "$s" ]]; then covered[$s]=1; fi
done
designs=()
for d in "${all_designs[@]}"; do
  if [[ -z "${covered[$d]:-}" ]]; then designs+=("$d"); fi
done
if [[ ${#designs[@]} == 0 ]]; then
  echo "reproduce_all: no design.json under $results" >&2
  exit 1
fi

# One design: its report in $logs/<n>.log, its exit code in $logs/<n>.rc.
export pronk results logs
export PRONK_REPRODUCE_OPTIONS="$*"
reproduce_one() {
  local n=$1 design=$2 rc=0
  # shellcheck disable=SC2086  # the options are plain flags, split on purpose
  (cd "$results/.." && "$pronk" reproduce "$(basename "$results")/$design" --threads 1 \
      $PRONK_REPRODUCE_OPTIONS) >"$logs/$n.log" 2>&1 || rc=$?
  echo "$rc" >"$logs/$n.rc"
}
export -f reproduce_one

start=$(date +%s)
for i in "${!designs[@]}"; do printf '%s\n%s\n' "$i" "${designs[$i]}"; done |
  xargs -d '\n' -n 2 -P "$jobs" bash -c 'reproduce_one "$1" "$2"' _

failed=0
for i in "${!designs[@]}"; do
  rc=$(cat "$logs/$i.rc")
  if [[ "$rc" == 0 ]]; then
    printf 'ok      %s: %s\n' "${designs[$i]}" "$(tail -n 1 "$logs/$i.log")"
  else
    failed=$((failed + 1))
    printf 'FAILED  %s (exit %s):\n' "${designs[$i]}" "$rc"
    sed 's/^/    /' "$logs/$i.log"
  fi
done
echo "reproduce_all: ${#designs[@]} designs, $failed failed, $(( $(date +%s) - start )) s" \
     "(${jobs} at once, options: ${PRONK_REPRODUCE_OPTIONS:-none})"
[[ $failed == 0 ]]
