#!/usr/bin/python3
"""The same robots and controller in pronk's full model and in MuJoCo ("model": "mujoco", Euler
at 0.5, 0.25 and 0.125 ms, its default): study 3's design and the tripod of results/family each on 32 validation
trials of its own study through `pronk compare --model` (stabilized and fallen fractions, hop
height error, mean duty, attitude error), and pr_running's own scene on 32 trials drawn here
(tilt <= 10 deg, lateral offset <= 0.2 m, horizontal kick <= 0.2 m/s; seed 36) through
`pronk simulate`; stance time and touchdown tilt from the strides after the fifth. Prints JSON
and writes it to --out (default results/bench/engine_agreement.json).

  bench/engine_agreement.py [--pronk build/pronk] [--threads 2] [--out FILE]
"""
import argparse
import csv
import json
import math
import os
import random
import statistics
import subprocess
import tempfile

from benchlib import ROOT, clock, run_timed, write_json_atomic

DESIGNS = {"study3_design": "results/study3_full_model_running/design.json",
           "tripod_design": "results/family/tripod/design.json"}
OTHER = {"study3_design": "tripod_design", "tripod_design": "study3_design"}
# (name, model, scene overrides): the full model, and MuJoCo at 0.5 ms, 0.25 ms and its default
# 0.125 ms (the refinement that tells which engine's answer is converged).
ENGINES = (("pseudo_rigid", "pseudo_rigid", []),
           ("mujoco_0.5ms", "mujoco", ['/mujoco={"timestep": 5e-4}']),
           ("mujoco_0.25ms", "mujoco", ['/mujoco={"timestep": 2.5e-4}']),
           ("mujoco_0.125ms", "mujoco", []))
TRIALS = 32


def stride_stats(strides_csv):
    """Mean stance time [s] and mean touchdown tilt [deg] over the strides after the fifth."""
    with open(strides_csv) as f:
        rows = [r for r in csv.DictReader(f) if int(r["stride"]) >= 5]
    if not rows:
        return None, None
    stance = statistics.mean(float(r["stance_duration"]) for r in rows)
    tilt = statistics.mean(math.hypot(float(r["roll_deg"]), float(r["pitch_deg"])) for r in rows)
    return stance, tilt


def compare_design(pronk, name, engine, threads, tmp):
    """One design on its own study's 32 validation trials in `engine`."""
    label_e, model, sets = engine
    out = os.path.join(tmp, "%s_%s" % (name, label_e))
    cmd = [pronk, "compare", os.path.join(ROOT, DESIGNS[name]),
           os.path.join(ROOT, DESIGNS[OTHER[name]]), "--model", model, "--trials", str(TRIALS),
           "--threads", str(threads), "--out", out, "--no-figures", "--quiet"]
    for o in sets:
        cmd += ["--set", o]
    wall = run_timed(cmd)
    label = os.path.basename(os.path.dirname(DESIGNS[name]))
    with open(os.path.join(out, "compare.csv")) as f:
        m = {r["metric"]: float(r[label]) for r in csv.DictReader(f) if r["set"] == "validation"}
    stance, tilt = stride_stats(os.path.join(out, "runs", label, "strides.csv"))
    return {"trials": TRIALS, "stabilized": m["stabilized"], "fell": m["fell"],
            "hop_height_error_m": m["hop_height_error"], "duty_mean": m["duty_mean"],
            "attitude_error": m["attitude_error"], "nominal_stance_s": stance,
            "nominal_touchdown_tilt_deg": tilt, "wall_s_both_designs": wall}


def draw_trials():
    rng = random.Random(36)
    trials = []
    for _ in range(TRIALS):
        tilt, heading = rng.uniform(0, 10), rng.uniform(0, 2 * math.pi)
        kick, kick_dir = rng.uniform(0, 0.2), rng.uniform(0, 2 * math.pi)
        trials.append({"attitude_deg": [tilt * math.cos(heading), tilt * math.sin(heading), 0],
                       "position": [0, rng.uniform(0, 0.2), 0.4],
                       "velocity": [0.3 + kick * math.cos(kick_dir), kick * math.sin(kick_dir),
                                    0]})
    return trials


def pr_running(pronk, engine, tmp):
    """pr_running's scene on the drawn trials in `engine`."""
    label_e, model, sets = engine
    rows, wall = [], 0.0
    for k, t in enumerate(draw_trials()):
        out = os.path.join(tmp, "pr_%s_%d" % (label_e, k))
        cmd = [pronk, "simulate", os.path.join(ROOT, "studies", "scenes", "pr_running.json"),
               "--model", model, "--set", "/initial=" + json.dumps(t), "--out", out,
               "--no-figures", "--quiet"]
        for o in sets:
            cmd += ["--set", o]
        t0 = clock()
        p = subprocess.run(cmd, capture_output=True, text=True)
        wall += clock() - t0
        if p.returncode not in (0, 1):
            raise SystemExit("bench: %s failed (%d): %s" % (" ".join(cmd), p.returncode, p.stderr))
        with open(os.path.join(out, "summary.json")) as f:
            s = json.load(f)
        stance, tilt = stride_stats(os.path.join(out, "strides.csv"))
        rows.append({"fell": s["status"] == "fell", "settled": s["metrics"]["settle_strides"] >= 0,
                     "apex_error": abs(s["metrics"]["last_apex_error_m"]),
                     "duty": s["metrics"]["mean_duty_cycle"], "stance": stance, "tilt": tilt})
    done = [r for r in rows if r["stance"] is not None]
    return {"trials": TRIALS, "stabilized": sum(r["settled"] for r in rows) / TRIALS,
            "fell": sum(r["fell"] for r in rows) / TRIALS,
            "last_apex_error_m": statistics.mean(r["apex_error"] for r in rows),
            "duty_mean": statistics.mean(r["duty"] for r in rows),
            "stance_s": statistics.mean(r["stance"] for r in done) if done else None,
            "touchdown_tilt_deg": statistics.mean(r["tilt"] for r in done) if done else None,
            "wall_s": wall}


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--pronk", default=os.path.join(ROOT, "build", "pronk"))
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--out", default=os.path.join(ROOT, "results", "bench", "engine_agreement.json"))
    a = ap.parse_args()
    doc = {"benchmark": "engine_agreement", "mujoco_integrator": "Euler", "rows": {}}
    with tempfile.TemporaryDirectory() as tmp:
        doc["rows"]["pr_running"] = {e[0]: pr_running(a.pronk, e, tmp) for e in ENGINES}
        for name in DESIGNS:
            doc["rows"][name] = {e[0]: compare_design(a.pronk, name, e, a.threads, tmp)
                                 for e in ENGINES}
    print(write_json_atomic(a.out, doc))


if __name__ == "__main__":
    main()
