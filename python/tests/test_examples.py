"""The examples run as tests: the notebook-style script, SciPy and Optuna on study 2.
The Optuna run uses PRONK_OPTUNA_TRIALS trials here (default 300, the full budget)."""
import json
import os
import pathlib
import subprocess
import sys

import pytest

EXAMPLES = pathlib.Path(__file__).resolve().parents[2] / "examples"


def run_example(name, *args):
    p = subprocess.run([sys.executable, str(EXAMPLES / name), *map(str, args)],
                       capture_output=True, text=True, env=dict(os.environ, MPLBACKEND="Agg"))
    assert p.returncode == 0, p.stdout + p.stderr
    return p.stdout


def test_notebook_script_simulates_plots_and_reads_a_design(tmp_path):
    png = tmp_path / "fig.png"
    out = run_example("notebook_simulate_plot.py", png)
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and png.stat().st_size > 10_000
    start = next(l for l in out.splitlines() if l.startswith("start"))
    tuned = next(l for l in out.splitlines() if l.startswith("study 2 tuned"))
    assert "fell" in start and "completed" in tuned  # the design's improvement, seen in one run
    assert "tuned parameters:" in out and "pulse_duration 0.3889" in out


def test_scipy_minimize_improves_study2_and_stays_feasible():
    out = run_example("scipy_minimize.py", "--maxiter", "60", "--threads", "2")
    line = next(l for l in out.splitlines() if l.strip().startswith("cost"))
    before, after = (float(v) for v in line.split(",")[0].split()[1::2])
    assert after < before
    assert "feasible True" in line


def test_optuna_tpe_on_study2_against_cobyla(tmp_path, record_property):
    trials = int(os.environ.get("PRONK_OPTUNA_TRIALS", "300"))
    out_json = tmp_path / "optuna.json"
    run_example("optuna_study2.py", "--trials", trials, "--threads", "2", "--json", out_json)
    res = json.loads(out_json.read_text())["results"]
    tpe, cobyla = res["optuna_tpe"], res["nlopt_cobyla"]
    assert tpe["evaluations"] == trials and cobyla["evaluations"] == 300
    record_property("optuna_validation_stabilized", tpe["validation_stabilized"])
    record_property("cobyla_validation_stabilized", cobyla["validation_stabilized"])
    print(f"Optuna TPE, {trials} trials: {100 * tpe['validation_stabilized']:.1f} % validation "
          f"stabilized (COBYLA, 300: {100 * cobyla['validation_stabilized']:.1f} %)")
    assert tpe["feasible"]
    if trials >= 300 and tpe["validation_stabilized"] < 0.95:
        pytest.xfail(f"Optuna TPE reached {100 * tpe['validation_stabilized']:.1f} % validation "
                     "stabilized in 300 trials (target 95 %; see docs/python.md)")
