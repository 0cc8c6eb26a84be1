#!/usr/bin/python3
"""`pronk map` in the full model at the size of a real robustness map: a 10 x 10
duty-cycle x tilt grid, 8 seeded trials of 10 s per cell (800 full-model runs,
pr_running with Verlet h = 1.5e-4 s, no boundary bisection, no stability fit),
timed as a whole job on --threads threads. Prints JSON and writes it to --out
(default results/bench/full_model_map.json).

  bench/full_model_map.py [--pronk build/pronk] [--threads 2] [--repeat 1] [--out FILE]
"""
import argparse
import json
import os
import shutil
import tempfile

from benchlib import ROOT, median, run_timed, write_json_atomic


def study(cells):
    return {
        "name": "bench_full_model_map",
        "kind": "map",
        "description": "bench: the full model over a 10 x 10 grid",
        "scene": os.path.join(ROOT, "studies", "scenes", "pr_running.json"),
        "scene_overrides": ["/pseudo_rigid/solver={\"method\": \"verlet\", \"h_fixed\": 1.5e-4}"],
        "models": ["pseudo_rigid"],
        "axes": [
            {"kind": "duty_cycle", "range": [0.1, 0.55], "count": cells},
            {"kind": "tilt_deg", "axis": [1, 0, 0], "range": [0, 18], "count": cells},
        ],
        "trials": {"count": 8, "seed": 101, "duration": 10, "tilt_deg": [0, 10],
                   "lateral_offset": [0, 0.2], "velocity_kick": [0, 0.2]},
        "stability": False,
        "boundary": {"max_steps": 0},
    }


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--pronk", default=os.path.join(ROOT, "build", "pronk"))
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--repeat", type=int, default=1)
    ap.add_argument("--cells", type=int, default=10)
    ap.add_argument("--out", default=os.path.join(ROOT, "results", "bench", "full_model_map.json"))
    a = ap.parse_args()
    tmp = tempfile.mkdtemp(prefix="pronk_bench_full_map_")
    path = os.path.join(tmp, "map.json")
    with open(path, "w") as f:
        json.dump(study(a.cells), f)
    times, summary = [], None
    for r in range(a.repeat):
        out = os.path.join(tmp, "out%d" % r)
        times.append(run_timed([a.pronk, "map", path, "-q", "--threads", str(a.threads),
                                "--out", out], what="pronk map"))
        with open(os.path.join(out, "summary.json")) as f:
            summary = json.load(f)
    shutil.rmtree(tmp)
    result = {
        "benchmark": "pronk map, full model, %d x %d cells x 8 trials x 10 s (whole job)" % (a.cells, a.cells),
        "threads": a.threads,
        "cores": os.cpu_count(),
        "runs": summary["totals"]["simulations"] if "simulations" in summary["totals"] else None,
        "wall_s_median": median(times),
        "wall_s": times,
        "target_s": 300,
        "stabilized_fraction": summary["totals"]["stabilized_fraction"],
    }
    print(write_json_atomic(a.out, result))


if __name__ == "__main__":
    main()
