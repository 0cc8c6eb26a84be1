#!/usr/bin/env bash
# Study 4: the problem of study 2 solved by several optimizers (NLopt local and
# global, and Ipopt with finite-difference gradients), same budget of 300
# evaluations; writes results/study4_<algorithm>/ and prints a markdown table
# (results/study4_comparison.md). Usage: scripts/study4_compare_optimizers.sh [threads]
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"
threads=${1:-2}
study=studies/study2_legged_pulse_duty50.json
run() {  # name, then --set overrides
  local name=$1; shift
  rm -rf "results/study4_$name"
  ./build/pronk optimize "$study" --threads "$threads" -q --out "results/study4_$name" \
    --set "/name=\"study4_$name\"" "$@"
}
run cobyla --set '/optimizer={"library":"nlopt","algorithm":"LN_COBYLA","max_evaluations":300,"seed":2}'
run bobyqa --set '/optimizer={"library":"nlopt","algorithm":"LN_BOBYQA","max_evaluations":300,"seed":2}'
run isres --set '/optimizer={"library":"nlopt","algorithm":"GN_ISRES","max_evaluations":300,"seed":2}'
run ipopt --set '/optimizer={"library":"ipopt","max_evaluations":300,"seed":2,"options":{"tol":1e-4}}'
python3 - <<'PY' | tee results/study4_comparison.md
import json
print("| optimizer | status | evaluations | failed | wall time [s] | best cost | feasible | spectral radius | validation: stabilized | validation: fell |")
print("|---|---|---|---|---|---|---|---|---|---|")
for name in ["cobyla", "bobyqa", "isres", "ipopt"]:
    d = json.load(open(f"results/study4_{name}/design.json"))
    o = d["optimizer"]; v = d["validation"]["metrics"]
    alg = o["library"] + (" " + o["algorithm"] if o["library"] == "nlopt" else "")
    print(f"| {alg} | {o['status']} | {o['evaluations']} | {o['failed_evaluations']} | {d['wall_time_s']:.2f} | "
          f"{d['cost']:.4f} | {'yes' if d['feasible'] else 'no'} | {d['metrics']['spectral_radius']:.3f} | "
          f"{v['stabilized']:.3f} | {v['fell']:.3f} |")
PY
