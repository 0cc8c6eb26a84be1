#!/usr/bin/env python3
"""Golden outputs of `pronk simulate`: every shipped scene, bit for bit.

    python3 scripts/golden.py make  PRONK_EXE   # rewrite tests/golden/ from this build
    python3 scripts/golden.py check PRONK_EXE   # rerun and compare (the CTest golden_simulate)

Each case runs `pronk simulate SCENE --set ... --out DIR -q` on a shipped scene (studies/scenes,
studies/mechanisms, the bench's quad hopper mechanism), its duration capped and its sampling
coarsened so the whole set stays small and fast, plus a few variants that reach code paths the
shipped scenes do not (disturbances, the small-angle formulation, the rigid-body robot, Verlet).
The CSVs are compared byte for byte; summary.json field by field after blanking the fields that
legitimately vary between runs and builds (VARYING: wall time, build information). The golden
files are the outputs of the code before a refactoring that must not change any result.
"""
import json
import os
import shutil
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
GOLDEN = os.path.join(ROOT, "tests", "golden")

DIST = ('/disturbances=[{"time": 0.9, "linear_impulse": [0.2, 0.3, 0], '
        '"angular_impulse": [0.002, -0.001, 0.001]}]')
DIST_BIG = ('/disturbances=[{"time": 0.9, "linear_impulse": [0.2, 0.3, 0], '
            '"angular_impulse": [0.02, -0.01, 0.01]}]')
# The full model's cases ran on RODAS4 (rtol 1e-6, atol 1e-8) before "auto" became the default;
# they name it so their goldens stand, and the *_auto cases follow the default.
RODAS4 = '/pseudo_rigid/solver={"method": "rodas4"}'
# The robot's body became rigid by default; the cases recorded on four masses name them so
# their goldens stand (the *_auto cases follow the defaults).
FOUR = '/pseudo_rigid/body="four_masses"'
DIST_FULL = ('/disturbances=[{"time": 0.7, "linear_impulse": [0.5, 0.8, 0], '
             '"angular_impulse": [0.01, -0.01, 0.005]}]')

# name -> (scene path, --set assignments)
CASES = {
    # The reduced models (impulse, pulse).
    "case1_body_only": ("studies/scenes/case1_body_only.json",
                        ["/simulation/duration=4", "/simulation/sample_interval=0.02"]),
    "case2_legged_impulse": ("studies/scenes/case2_legged_impulse.json",
                             ["/simulation/duration=4", "/simulation/sample_interval=0.02"]),
    "case3_legged_pulse": ("studies/scenes/case3_legged_pulse.json",
                           ["/simulation/duration=4", "/simulation/sample_interval=0.02"]),
    "case3_small_angle_disturbed": ("studies/scenes/case3_legged_pulse.json",
                                    ["/simulation/duration=3", "/simulation/sample_interval=0.02",
                                     '/attitude="small_angle_euler123"', DIST]),
    "case3_small_angle_warns": ("studies/scenes/case3_legged_pulse.json",
                                ["/simulation/duration=3", "/simulation/sample_interval=0.02",
                                 '/attitude="small_angle_euler123"', DIST_BIG]),
    "case2_max_strides": ("studies/scenes/case2_legged_impulse.json",
                          ["/simulation/max_strides=3", "/simulation/sample_interval=0.02"]),
    "case3_tilt_fall": ("studies/scenes/case3_legged_pulse.json",
                        ["/simulation/duration=3", "/simulation/sample_interval=0.02",
                         '/disturbances=[{"time": 0.9, "linear_impulse": [0, 0, 0], '
                         '"angular_impulse": [0.5, 0.3, 0]}]']),
    "fidelity_duty15": ("studies/scenes/fidelity_duty15.json",
                        ["/simulation/sample_interval=0.02"]),
    "legged_pulse_duty50": ("studies/scenes/legged_pulse_duty50.json",
                            ["/simulation/sample_interval=0.05"]),
    # The full (pseudo-rigid) model.
    "case5_pr_hop_height": ("studies/scenes/case5_pr_hop_height.json",
                            ["/simulation/duration=1.5", "/simulation/sample_interval=0.02", RODAS4, FOUR]),
    "case5_rigid_disturbed": ("studies/scenes/case5_pr_hop_height.json",
                              ["/simulation/duration=1.2", "/simulation/sample_interval=0.02",
                               '/pseudo_rigid/body="rigid"',
                               DIST_FULL, RODAS4]),
    "case6_pr_drop": ("studies/scenes/case6_pr_drop.json",
                      ["/simulation/duration=1.5", "/simulation/sample_interval=0.02", RODAS4, FOUR]),
    "case7_pr_height_change": ("studies/scenes/case7_pr_height_change.json",
                               ["/simulation/duration=1.5", "/simulation/sample_interval=0.02", RODAS4, FOUR]),
    "pr_running": ("studies/scenes/pr_running.json",
                   ["/simulation/duration=1.2", "/simulation/sample_interval=0.02", RODAS4, FOUR]),
    "pr_running_auto": ("studies/scenes/pr_running.json",
                        ["/simulation/duration=1.2", "/simulation/sample_interval=0.02"]),
    "case5_auto": ("studies/scenes/case5_pr_hop_height.json",
                   ["/simulation/duration=1.5", "/simulation/sample_interval=0.02"]),
    "pr_running_verlet": ("studies/scenes/pr_running.json",
                          ["/simulation/duration=1.2", "/simulation/sample_interval=0.02",
                           '/pseudo_rigid/solver={"method": "verlet", "h_fixed": 5e-5}', FOUR]),
    "case6_low_fall": ("studies/scenes/case6_pr_drop.json",
                       ["/simulation/duration=1.5", "/simulation/sample_interval=0.02",
                        "/simulation/fall/min_height=0.3", RODAS4, FOUR]),
    "case5_euler_diverges": ("studies/scenes/case5_pr_hop_height.json",
                             ["/simulation/duration=1", "/simulation/sample_interval=0.02",
                              '/pseudo_rigid/solver={"method": "euler", "h_fixed": 2e-3}', FOUR]),
    "case5_step_budget": ("studies/scenes/case5_pr_hop_height.json",
                          ["/simulation/duration=1", "/simulation/sample_interval=0.02",
                           '/pseudo_rigid/solver={"method": "rodas4", "max_steps": 1500}', FOUR]),
    "fidelity_duty15_full": ("studies/scenes/fidelity_duty15.json",
                             ['/model="pseudo_rigid"', "/simulation/duration=1.2",
                              "/simulation/sample_interval=0.02", RODAS4, FOUR]),
    # Generic pseudo-rigid mechanisms.
    "explicit_instability": ("studies/mechanisms/explicit_instability.json",
                             ["/simulation/output_interval=0.02"]),
    "four_leg_drop": ("studies/mechanisms/four_leg_drop.json",
                      ["/simulation/t_end=0.6", "/simulation/output_interval=0.02"]),
    "pendulum": ("studies/mechanisms/pendulum.json",
                 ["/simulation/t_end=3", "/simulation/output_interval=0.05"]),
    "satellite": ("studies/mechanisms/satellite.json",
                  ["/simulation/t_end=2", "/simulation/output_interval=0.05"]),
    "spring_leg_drop": ("studies/mechanisms/spring_leg_drop.json",
                        ["/simulation/t_end=2", "/simulation/output_interval=0.02"]),
    "quad_hopper_mechanism": ("results/bench/quad_hopper_mechanism.json",
                              ["/simulation/t_end=1.5", "/simulation/output_interval=0.02"]),
    "quad_hopper_verlet": ("results/bench/quad_hopper_mechanism.json",
                           ["/simulation/t_end=1.5", "/simulation/output_interval=0.02",
                            '/simulation/method="verlet"', "/simulation/h_fixed=5e-4"]),
    "pendulum_step_budget": ("studies/mechanisms/pendulum.json",
                             ["/simulation/t_end=3", "/simulation/output_interval=0.05",
                              "/simulation/max_steps=3000"]),
}

# summary.json fields (JSON Pointers) that legitimately differ between runs and builds.
VARYING = ["/commit", "/cost/wall_time_s"]
KEPT_FILES = (".csv", "summary.json")


def run_case(exe, name, out_dir):
    scene, sets = CASES[name]
    cmd = [exe, "simulate", os.path.join(ROOT, scene), "--out", out_dir, "-q"]
    for s in sets:
        cmd += ["--set", s]
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode not in (0, 1):  # 1: the run fell or diverged (outputs still written)
        raise RuntimeError(f"{name}: exit {p.returncode}: {p.stderr.strip()}")
    return p.returncode


def blank(doc, pointer):
    parts = pointer.strip("/").split("/")
    node = doc
    for p in parts[:-1]:
        if not isinstance(node, dict) or p not in node:
            return
        node = node[p]
    if isinstance(node, dict) and parts[-1] in node:
        node[parts[-1]] = "<varies>"


def normalized_summary(path):
    with open(path) as f:
        doc = json.load(f)
    for ptr in VARYING:
        blank(doc, ptr)
    return json.dumps(doc, indent=1, sort_keys=True) + "\n"


def kept(files):
    return sorted(f for f in files if f.endswith(KEPT_FILES))


def make(exe):
    if os.path.isdir(GOLDEN):
        shutil.rmtree(GOLDEN)
    for name in CASES:
        with tempfile.TemporaryDirectory() as tmp:
            code = run_case(exe, name, tmp)
            dst = os.path.join(GOLDEN, name)
            os.makedirs(dst)
            for f in kept(os.listdir(tmp)):
                if f == "summary.json":
                    with open(os.path.join(dst, f), "w") as out:
                        out.write(normalized_summary(os.path.join(tmp, f)))
                else:
                    shutil.copyfile(os.path.join(tmp, f), os.path.join(dst, f))
            with open(os.path.join(dst, "exit_code"), "w") as out:
                out.write(f"{code}\n")
        print(f"{name}: exit {code}")


def check(exe):
    failures = []
    for name in CASES:
        gold = os.path.join(GOLDEN, name)
        if not os.path.isdir(gold):
            failures.append(f"{name}: no golden files (python3 scripts/golden.py make)")
            continue
        with tempfile.TemporaryDirectory() as tmp:
            code = run_case(exe, name, tmp)
            with open(os.path.join(gold, "exit_code")) as f:
                want_code = int(f.read())
            if want_code != code:
                failures.append(f"{name}: exit code {code}, golden {want_code}")
            want = kept(os.listdir(gold))
            got = kept(os.listdir(tmp))
            if want != got:
                failures.append(f"{name}: files {got}, golden {want}")
            for f in want:
                if f not in got:
                    continue
                if f == "summary.json":
                    same = normalized_summary(os.path.join(tmp, f)) == open(
                        os.path.join(gold, f)).read()
                else:
                    with open(os.path.join(tmp, f), "rb") as a, open(os.path.join(gold, f),
                                                                      "rb") as b:
                        same = a.read() == b.read()
                if not same:
                    failures.append(f"{name}/{f} differs from tests/golden/{name}/{f}")
        print(f"{name}: {'ok' if not any(x.startswith(name) for x in failures) else 'DIFFERS'}")
    for f in failures:
        print("FAIL " + f)
    return 1 if failures else 0


if __name__ == "__main__":
    if len(sys.argv) != 3 or sys.argv[1] not in ("make", "check"):
        print(__doc__)
        sys.exit(2)
    if sys.argv[1] == "make":
        make(sys.argv[2])
        sys.exit(0)
    sys.exit(check(sys.argv[2]))
