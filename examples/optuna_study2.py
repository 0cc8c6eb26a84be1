#!/usr/bin/python3
"""Study 2 (legged pulse model at ~50 % duty) tuned by Optuna's TPE sampler through
pronk.Study, compared with the shipped COBYLA result (pronk optimize) at the same budget.

    PYTHONPATH=build/python /usr/bin/python3 examples/optuna_study2.py [--trials 300]
        [--seed 2] [--constraints penalty|native] [--threads 0] [--json OUT.json]

Each trial evaluates the study's 16 disturbed scenarios. The constraints (spectral radius
<= 0.8, 0.4 <= mean duty <= 0.5) become pronk's quadratic penalty, cost + w * sum(max(g, 0)^2)
with the study's penalty_weight w (what pronk optimize does for NLopt algorithms without
constraint support), or, with --constraints native, go to TPE's constraints_func. The best
feasible trial is then checked on the study's 64 held-out validation trials, like pronk
optimize does.
"""
import argparse
import json
import pathlib
import time
import warnings

import optuna

import pronk

ROOT = pathlib.Path(__file__).resolve().parents[1]
STUDY = ROOT / "studies" / "study2_legged_pulse_duty50.json"
COBYLA = ROOT / "results" / "study2_legged_pulse_duty50" / "design.json"


def tune(study, trials, seed, native):
    """Optuna TPE over the study's parameters (log-scaled where the study says so)."""
    weight = study.document.get("optimizer", {}).get("penalty_weight", 1000.0)

    def objective(trial):
        x = [trial.suggest_float(n, lo, hi, log=log)
             for n, lo, hi, log in zip(study.names, study.lower, study.upper, study.log_scale)]
        cost, g, metrics = study.evaluate(x)
        trial.set_user_attr("constraints", [float(v) for v in g])
        trial.set_user_attr("cost", cost)
        return cost if native else cost + weight * sum(max(v, 0.0) ** 2 for v in g)

    if native:
        sampler = optuna.samplers.TPESampler(
            seed=seed, constraints_func=lambda t: t.user_attrs["constraints"])
    else:
        sampler = optuna.samplers.TPESampler(seed=seed)
    tpe = optuna.create_study(direction="minimize", sampler=sampler)
    tpe.enqueue_trial(dict(zip(study.names, map(float, study.initial))))  # COBYLA's start too
    tpe.optimize(objective, n_trials=trials)
    return tpe


def best_trial(tpe):
    """The feasible trial of least cost; without one, the least infeasible trial."""
    feasible = [t for t in tpe.trials if max(t.user_attrs["constraints"]) <= 0]
    if feasible:
        return min(feasible, key=lambda t: t.user_attrs["cost"]), True
    return min(tpe.trials, key=lambda t: max(t.user_attrs["constraints"])), False


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--trials", type=int, default=300)
    ap.add_argument("--seed", type=int, default=2)
    ap.add_argument("--constraints", choices=["penalty", "native"], default="penalty")
    ap.add_argument("--threads", type=int, default=0)
    ap.add_argument("--json", help="write the comparison here")
    args = ap.parse_args()
    optuna.logging.set_verbosity(optuna.logging.WARNING)
    warnings.filterwarnings("ignore", category=optuna.exceptions.ExperimentalWarning)

    study = pronk.Study(STUDY, threads=args.threads)
    t0 = time.perf_counter()
    tpe = tune(study, args.trials, args.seed, args.constraints == "native")
    wall = time.perf_counter() - t0
    best, feasible = best_trial(tpe)
    x = [best.params[n] for n in study.names]
    cost, g, metrics = study.evaluate(x)
    vcost, _, vmetrics = study.validation().evaluate(x)

    cobyla = pronk.read_design(COBYLA)
    rows = {
        "optuna_tpe": {"evaluations": len(tpe.trials), "wall_time_s": wall,
                       "constraints": args.constraints,
                       "feasible_trials": sum(max(t.user_attrs["constraints"]) <= 0
                                              for t in tpe.trials),
                       "feasible": feasible, "best_cost": cost,
                       "spectral_radius": metrics["spectral_radius"],
                       "duty_mean": metrics["duty_mean"],
                       "validation_stabilized": vmetrics["stabilized"],
                       "validation_cost": vcost,
                       "parameters": dict(zip(study.names, map(float, x)))},
        "nlopt_cobyla": {"evaluations": cobyla["optimizer"]["evaluations"],
                         "wall_time_s": cobyla["wall_time_s"],
                         "feasible": cobyla["feasible"], "best_cost": cobyla["cost"],
                         "spectral_radius": cobyla["metrics"]["spectral_radius"],
                         "duty_mean": cobyla["metrics"]["duty_mean"],
                         "validation_stabilized": cobyla["validation"]["metrics"]["stabilized"],
                         "validation_cost": cobyla["validation"]["cost"],
                         "parameters": cobyla["parameters"]},
    }
    print(f"Optuna TPE (seed {args.seed}, constraints: {args.constraints}): "
          f"{rows['optuna_tpe']['feasible_trials']} of {len(tpe.trials)} trials feasible")
    print(f"study 2, budget {args.trials} evaluations (16 scenarios each), "
          f"validation on {study.validation().scenarios} held-out trials")
    print(f"{'optimizer':14} {'evals':>5} {'wall [s]':>8} {'cost':>8} {'feasible':>8} "
          f"{'rho':>6} {'duty':>6} {'val. stabilized':>16}")
    for name, r in rows.items():
        print(f"{name:14} {r['evaluations']:5d} {r['wall_time_s']:8.2f} {r['best_cost']:8.3f} "
              f"{str(r['feasible']):>8} {r['spectral_radius']:6.3f} {r['duty_mean']:6.3f} "
              f"{100 * r['validation_stabilized']:15.1f}%")
    if args.json:
        out = {"study": STUDY.name, "trials": args.trials, "seed": args.seed,
               "pronk_version": pronk.__version__, "pronk_commit": pronk.commit,
               "optuna_version": optuna.__version__, "results": rows}
        pathlib.Path(args.json).parent.mkdir(parents=True, exist_ok=True)
        pathlib.Path(args.json).write_text(json.dumps(out, indent=2) + "\n")


if __name__ == "__main__":
    main()
