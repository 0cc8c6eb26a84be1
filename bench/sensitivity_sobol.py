#!/usr/bin/python3
"""`pronk sensitivity` at the size of a real global analysis: Sobol indices of study 2's
design (pulse model, its 16 scenarios of 12 s) over 6 numbers (the mass, the three
principal moments, the pulse duration and the hop height, each +-10 % or the inertia's
triangle limit) at N = 1024 base samples, N (k + 2) = 8192 evaluations plus the 25 local
ones, timed as a whole process on 1 thread and on --threads threads, --repeat times each,
alternating. Prints JSON (medians and the ratio of the medians, measured in one run) and
writes it to --out (default results/bench/sensitivity_sobol.json). The target: <= 60 s on
2 cores.

  bench/sensitivity_sobol.py [--pronk build/pronk] [--threads 2] [--repeat 3] [--out FILE]
"""
import argparse
import json
import os
import shutil
import tempfile

from benchlib import ROOT, median, run_timed, write_json_atomic

INPUTS = ["/body/mass", "/body/inertia_tensor/0/0", "/body/inertia_tensor/1/1",
          "/body/inertia_tensor/2/2", "/pulse/duration", "/controller/hop_height"]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--pronk", default=os.path.join(ROOT, "build", "pronk"))
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--samples", type=int, default=1024)
    ap.add_argument("--out", default=os.path.join(ROOT, "results", "bench", "sensitivity_sobol.json"))
    a = ap.parse_args()
    design = os.path.join(ROOT, "results", "study2_legged_pulse_duty50", "design.json")
    tmp = tempfile.mkdtemp(prefix="pronk_bench_sobol_")
    times = {1: [], a.threads: []}
    summary = None
    for r in range(a.repeat):
        for t in (1, a.threads):
            out = os.path.join(tmp, "t%d_%d" % (t, r))
            times[t].append(run_timed(
                [a.pronk, "sensitivity", design, "--samples", str(a.samples), "--threads", str(t),
                 "--no-figures", "-q", "--out", out, "--inputs"] + INPUTS, what="pronk sensitivity"))
            with open(os.path.join(out, "sensitivity.json")) as f:
                summary = json.load(f)
    shutil.rmtree(tmp)
    one, many = median(times[1]), median(times[a.threads])
    result = {
        "benchmark": "pronk sensitivity, study 2's design (pulse model, 16 trials x 12 s), "
                     "Sobol N = %d over 6 numbers (whole process)" % a.samples,
        "inputs": INPUTS,
        "evaluations": summary.get("evaluations"),
        "cores": os.cpu_count(),
        "threads": a.threads,
        "wall_s_median_1_thread": one,
        "wall_s_median": many,
        "speedup": one / many,
        "wall_s_1_thread": times[1],
        "wall_s": times[a.threads],
        "target_s": 60,
    }
    print(write_json_atomic(a.out, result))


if __name__ == "__main__":
    main()
