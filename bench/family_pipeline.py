#!/usr/bin/python3
"""The whole `pronk design` pipeline of family robots (pulse stage, full stage, validation,
the pages), timed as whole processes on --threads threads, one robot after another. For
each robot: the process's wall time, the design's own clock (design.json's wall_time_s),
each stage's evaluations and median evaluation time, and whether the design it made is the
committed one (results/family/<robot>/design.json: the same parameters bit for bit, and the
same validation outcome). Prints JSON and writes it to --out (default
results/bench/family_pipeline.json). Run it alone on the machine: the times are the point.

  bench/family_pipeline.py [--pronk build/pronk] [--threads 2] [--robots a,b] [--out FILE]
                           [--keep DIR] [--figures] [-- DESIGN OPTIONS...]

Options after `--` go to every `pronk design` (a quick check of the script itself:
`-- --budget 2 --pulse-budget 2 --trials 2 --validation 2 --duration 1`; its designs are then
not the committed ones, and the JSON says so).
"""
import argparse
import csv
import json
import os
import platform
import shutil
import statistics
import subprocess
import tempfile

from benchlib import ROOT, run_timed, write_json_atomic

FAMILY = os.path.join(ROOT, "studies", "scenes", "family")
COMMITTED = os.path.join(ROOT, "results", "family")
TARGET_MIN = 15.0  # the pipeline's budget per robot [min]


def stage_times(out):
    """Per stage: evaluations and the median evaluation wall time [s] (timings.csv)."""
    stages = {}
    root = os.path.join(out, "stages")
    for name in sorted(os.listdir(root)):
        path = os.path.join(root, name, "timings.csv")
        if not os.path.exists(path):
            continue
        with open(path) as f:
            walls = [float(r["wall_time_s"]) for r in csv.DictReader(f)]
        stages[name] = {"evaluations": len(walls),
                        "median_evaluation_s": statistics.median(walls) if walls else None,
                        "sum_evaluations_s": sum(walls)}
    return stages


def same_design(mine, committed):
    """Whether two design.json files hold the same tuned parameters (bit for bit) and the
    same validation outcome; the fields that differ otherwise."""
    differ = [k for k in ("parameters", "validation", "cost") if mine.get(k) != committed.get(k)]
    return not differ, differ


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--pronk", default=os.path.join(ROOT, "build", "pronk"))
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--robots", default="",
                    help="comma-separated robot names (default: every scene in the family)")
    ap.add_argument("--figures", action="store_true",
                    help="render the SVG figures too (default: --no-figures)")
    ap.add_argument("--keep", default="", help="keep each robot's output under DIR/<robot>")
    ap.add_argument("--out", default=os.path.join(ROOT, "results", "bench", "family_pipeline.json"))
    ap.add_argument("design_options", nargs="*", help="after --: options for pronk design")
    a = ap.parse_args()
    robots = [r for r in a.robots.split(",") if r] or sorted(
        f[:-5] for f in os.listdir(FAMILY) if f.endswith(".json"))
    tmp = tempfile.mkdtemp(prefix="pronk_bench_family_")
    rows = []
    for r in robots:
        out = os.path.join(a.keep, r) if a.keep else os.path.join(tmp, r)
        if os.path.exists(out):
            shutil.rmtree(out)
        cmd = [a.pronk, "design", os.path.join("studies", "scenes", "family", r + ".json"),
               "--out", out, "-q", "--threads", str(a.threads)]
        if not a.figures:
            cmd.append("--no-figures")
        cmd += a.design_options
        # From the source tree, as scripts/family.sh runs it: the study names relative paths.
        cwd = os.getcwd()
        os.chdir(ROOT)
        try:
            wall = run_timed(cmd, what="pronk design " + r)
        finally:
            os.chdir(cwd)
        with open(os.path.join(out, "design.json")) as f:
            mine = json.load(f)
        row = {"robot": r, "process_wall_s": wall, "process_wall_min": wall / 60.0,
               "own_clock_s": mine.get("wall_time_s"), "stages": stage_times(out)}
        committed = os.path.join(COMMITTED, r, "design.json")
        if os.path.exists(committed):
            with open(committed) as f:
                same, differ = same_design(mine, json.load(f))
            row["same_as_committed"] = same
            row["differs_in"] = differ
        row["within_target"] = wall / 60.0 <= TARGET_MIN
        rows.append(row)
        print("%s: %.1f min (own clock %.1f min)%s" % (
            r, wall / 60.0, (mine.get("wall_time_s") or 0.0) / 60.0,
            "" if row.get("same_as_committed", True) else ", NOT the committed design"))
    shutil.rmtree(tmp)
    result = {
        "benchmark": "pronk design on each family robot, the whole process (default options)",
        "threads": a.threads,
        "figures": a.figures,
        "design_options": a.design_options,
        "machine": {"cpus": os.cpu_count(), "processor": platform.processor() or platform.machine(),
                    "load_before": os.getloadavg()},
        "pronk_version": subprocess.run([a.pronk, "--version"], stdout=subprocess.PIPE,
                                        text=True).stdout.strip(),
        "target_min": TARGET_MIN,
        "robots": rows,
    }
    print(write_json_atomic(a.out, result))


if __name__ == "__main__":
    main()
