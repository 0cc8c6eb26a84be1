#!/usr/bin/python3
"""Study 2 tuned with scipy.optimize.minimize (COBYLA) through pronk.Study, in the
optimizer's unit coordinates, then checked on the held-out validation trials.

    PYTHONPATH=build/python /usr/bin/python3 examples/scipy_minimize.py [--maxiter 300]
"""
import argparse
import pathlib

import numpy as np
from scipy.optimize import minimize

import pronk

ROOT = pathlib.Path(__file__).resolve().parents[1]
STUDY = ROOT / "studies" / "study2_legged_pulse_duty50.json"


class Cached:
    """SciPy asks for the cost and each constraint separately: one evaluation per point."""

    def __init__(self, study):
        self.study, self.x, self.value, self.count = study, None, None, 0

    def __call__(self, x):
        x = np.clip(x, 0.0, 1.0)  # COBYLA may step just outside the bounds
        if self.x is None or not np.array_equal(x, self.x):
            self.x, self.value = x.copy(), self.study.evaluate(x)
            self.count += 1
        return self.value


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--maxiter", type=int, default=300)
    ap.add_argument("--threads", type=int, default=0)
    args = ap.parse_args()

    study = pronk.Study(STUDY, threads=args.threads, unit=True)
    f = Cached(study)
    n = len(study.names)
    constraints = [{"type": "ineq", "fun": lambda x, j=j: -f(x)[1][j]}  # SciPy: >= 0 feasible
                   for j in range(len(study.constraint_names))]
    constraints += [{"type": "ineq", "fun": lambda x, i=i: x[i]} for i in range(n)]
    constraints += [{"type": "ineq", "fun": lambda x, i=i: 1 - x[i]} for i in range(n)]
    res = minimize(lambda x: f(x)[0], study.initial, method="COBYLA", constraints=constraints,
                   options={"maxiter": args.maxiter, "rhobeg": 0.1})
    x = np.clip(res.x, 0.0, 1.0)
    cost, g, m = study.evaluate(x)
    _, _, vm = study.validation().evaluate(x)
    print(f"scipy COBYLA: {res.message} ({f.count} evaluations)")
    print(f"  cost {study.evaluate(study.initial)[0]:.4f} -> {cost:.4f}, feasible {bool((g <= 0).all())}, "
          f"rho {m['spectral_radius']:.3f}, duty {m['duty_mean']:.3f}")
    print(f"  validation: {100 * vm['stabilized']:.1f} % of {study.validation().scenarios} "
          f"held-out trials stabilized")
    for name, v in zip(study.names, study.from_unit(x)):
        print(f"  {name:16} {v:.6g}")


if __name__ == "__main__":
    main()
