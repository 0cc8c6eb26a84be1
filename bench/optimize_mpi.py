#!/usr/bin/python3
"""`pronk optimize` on MPI ranks: a full-model stage (study 3's full stage, made
short) timed as a whole job at 1 thread (plain), and under mpirun at 1, 2 and 4
ranks; the journal of every run is checked against the 1-thread run's bytes.
Prints JSON and writes it to --out (default results/bench/optimize_mpi.json).

  bench/optimize_mpi.py [--pronk build/pronk] [--repeat 3] [--evaluations 4] [--out FILE]

Medians over --repeat runs, ratios from the same run of this script. On a
machine with fewer cores than ranks the extra ranks share cores (--oversubscribe).
"""
import argparse
import json
import os
import shutil
import sys
import tempfile

from benchlib import ROOT, median, run_timed, write_json_atomic


def full_stage_study(evaluations):
    with open(os.path.join(ROOT, "studies", "study3_full_model_running.json")) as f:
        doc = json.load(f)
    doc["name"] = "bench_optimize_mpi"
    doc["scene"] = os.path.join(ROOT, "studies", "scenes", "pr_running.json")
    doc["model"] = "pseudo_rigid"
    for key in ("stages", "validation"):
        doc.pop(key, None)
    doc["optimizer"]["max_evaluations"] = evaluations
    return doc


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--pronk", default=os.path.join(ROOT, "build", "pronk"))
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--evaluations", type=int, default=4)
    ap.add_argument("--out", default=os.path.join(ROOT, "results", "bench", "optimize_mpi.json"))
    a = ap.parse_args()
    mpirun = shutil.which("mpirun")
    if not mpirun:
        sys.exit("bench: mpirun not found (scripts/setup.sh installs openmpi-bin)")
    tmp = tempfile.mkdtemp(prefix="pronk_bench_optimize_mpi_")
    study = os.path.join(tmp, "study.json")
    doc = full_stage_study(a.evaluations)
    with open(study, "w") as f:
        json.dump(doc, f)
    configs = [("1 thread", None, ["--threads", "1"])]
    for n in (1, 2, 4):
        # One rank is a plain one-process run (no MPI_Init): one thread, like each rank.
        configs.append(("%d MPI ranks" % n, n, ["--threads", "1"]))
    rows, reference = [], None
    for name, ranks, extra in configs:
        times = []
        for r in range(a.repeat):
            out = os.path.join(tmp, "run_%s_%d" % (name.replace(" ", "_"), r))
            cmd = [a.pronk, "optimize", study, "-q", "--out", out] + extra
            if ranks is not None:
                cmd = [mpirun, "--allow-run-as-root", "--oversubscribe", "-np", str(ranks)] + cmd
            times.append(run_timed(cmd))
            with open(os.path.join(out, "journal.jsonl"), "rb") as f:
                journal = f.read()
            if reference is None:
                reference = journal
            elif journal != reference:
                sys.exit("bench: %s wrote a different journal" % name)
            shutil.rmtree(out)
        rows.append({"workers": name, "ranks": ranks, "wall_s_median": median(times),
                     "wall_s": times})
    base = rows[0]["wall_s_median"]
    for row in rows:
        row["speedup_over_1_thread"] = base / row["wall_s_median"]
    one_rank = rows[1]["wall_s_median"]
    for row in rows[1:]:
        row["speedup_over_1_rank"] = one_rank / row["wall_s_median"]
    result = {
        "benchmark": "pronk optimize across MPI ranks (whole job)",
        "study": "study 3's full-model stage: %d evaluations x %d scenarios x %g s, pseudo_rigid, Verlet"
                 % (a.evaluations, doc["scenarios"]["random"]["count"], doc["scenarios"]["duration"]),
        "cores": os.cpu_count(),
        "repeat": a.repeat,
        "journals_identical": True,
        "rows": rows,
    }
    shutil.rmtree(tmp)
    print(write_json_atomic(a.out, result))


if __name__ == "__main__":
    main()
