#!/usr/bin/python3
"""Benchmark: the cost of calling the objective API from Python. Study 2's evaluation
(16 scenarios, pulse model, stride-map stability) through pronk.Study.evaluate against
the same C++ evaluator called in a C++ loop (Study._time_native: no Python between
evaluations), on 1 thread, interleaved rounds. The overhead is judged on the fastest
round of each (the work is deterministic: on a shared machine the minimum is the
least disturbed estimate); medians are reported beside. A paired figure is the
most robust on a loaded machine: per call, the time Study.evaluate takes minus the
C++ evaluator's own wall time inside that call (Study.last_wall_time): what the
binding adds (argument and result conversion, GIL release and reacquisition).
Prints one JSON object.

    PYTHONPATH=build/python /usr/bin/python3 bench/bench_python.py [rounds] [per_round]
"""
import json
import pathlib
import statistics
import sys

import numpy as np

import pronk
from benchlib import clock, median

ROOT = pathlib.Path(__file__).resolve().parents[1]


def main():
    rounds = int(sys.argv[1]) if len(sys.argv) > 1 else 15
    per_round = int(sys.argv[2]) if len(sys.argv) > 2 else 20
    study = pronk.Study(ROOT / "studies" / "study2_legged_pulse_duty50.json", threads=1)
    design = pronk.read_design(ROOT / "results" / "study2_legged_pulse_duty50" / "design.json")
    points = {"initial": np.array(study.initial), "tuned": study.from_unit(design["unit"])}
    out = {"benchmark": "python_objective_overhead", "study": "study2_legged_pulse_duty50",
           "threads": 1, "rounds": rounds, "evaluations_per_round": per_round,
           "pronk_version": pronk.__version__, "commit": pronk.commit, "points": {}}
    for name, x in points.items():
        study.evaluate(x)  # warm up
        py, native, paired = [], [], []
        for _ in range(rounds):
            for _ in range(per_round):
                t0 = clock()
                study.evaluate(x)
                dt = clock() - t0
                paired.append((dt - study.last_wall_time, study.last_wall_time))
            t0 = clock()
            for _ in range(per_round):
                study.evaluate(x)
            py.append((clock() - t0) / per_round)
            native.append(statistics.fmean(study._time_native(x, per_round)))
        mpy, mnat = median(py), median(native)
        bpy, bnat = min(py), min(native)
        out["points"][name] = {
            "python_evaluate_min_s": bpy,
            "native_evaluate_min_s": bnat,
            "overhead_per_evaluation_s": bpy - bnat,
            "overhead_relative": (bpy - bnat) / bnat,
            "python_evaluate_median_s": mpy,
            "native_evaluate_median_s": mnat,
            "overhead_relative_medians": (mpy - mnat) / mnat,
            "paired_binding_overhead_median_s": median(p[0] for p in paired),
            "paired_binding_overhead_relative_median": median(p[0] / p[1] for p in paired),
        }
    # The target is judged on the paired figure (the end-to-end ones are within the
    # machine's noise; reported beside it).
    out["max_overhead_relative"] = max(p["paired_binding_overhead_relative_median"]
                                       for p in out["points"].values())
    out["target_overhead_relative"] = 0.05
    out["met"] = out["max_overhead_relative"] <= 0.05
    print(json.dumps(out, indent=2))


if __name__ == "__main__":
    main()
