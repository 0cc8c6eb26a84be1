#!/usr/bin/env bash
# The seed's controller (impulse hop-height law, hand-tuned gains of the
# legged scenes) on study 2's 64 held-out disturbed trials, for pulse
# durations from ~20 % to ~50 % duty, beside the tuned design of study 2.
# Prints a markdown table (results/study2_seed_baseline.md).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"
tmp=$(mktemp -d)
study=studies/study2_legged_pulse_duty50.json
for T in 0.1 0.15 0.2 0.25 0.3 0.4; do
  ./build/pronk optimize "$study" -q --out "$tmp/seed_$T" \
    --set '/scene_overrides=["/controller/pulse_aware_hop=false", "/pulse/duration='"$T"'"]' \
    --set '/parameters=[{"name":"bank_kp","pointer":"/controller/bank/kp","lower":0.001,"upper":1}]' \
    --set '/optimizer={"library":"nlopt","algorithm":"LN_COBYLA","max_evaluations":1}'
done
python3 - "$tmp" <<'PY' | tee results/study2_seed_baseline.md
import json, sys
tmp = sys.argv[1]
print("| design | pulse duration [s] | mean duty | stabilized (64 trials) | fell |")
print("|---|---|---|---|---|")
for T in ["0.1", "0.15", "0.2", "0.25", "0.3", "0.4"]:
    v = json.load(open(f"{tmp}/seed_{T}/design.json"))["validation"]["initial_metrics"]
    print(f"| seed controller | {T} | {v['duty_mean']:.3f} | {v['stabilized']:.3f} | {v['fell']:.3f} |")
d = json.load(open("results/study2_legged_pulse_duty50/design.json"))
v = d["validation"]["metrics"]
print(f"| study 2 tuned (pulse-aware hop law) | {d['parameters']['pulse_duration']:.3f} | {v['duty_mean']:.3f} | {v['stabilized']:.3f} | {v['fell']:.3f} |")
PY
rm -rf "$tmp"
