"""pronk.Study (the objective API), pronk.reproduce and pronk.run_map against the C++
engines and the CLI: the same values, whatever the thread count."""
import csv
import json

import numpy as np
import pytest

import pronk


@pytest.fixture(scope="module")
def study2_path(source_dir):
    return source_dir / "studies" / "study2_legged_pulse_duty50.json"


@pytest.fixture(scope="module")
def design2(source_dir):
    return pronk.read_design(source_dir / "results" / "study2_legged_pulse_duty50" / "design.json")


def test_names_bounds_initial_are_the_study_files(study2_path):
    doc = json.loads(study2_path.read_text())
    s = pronk.Study(study2_path, threads=1)
    assert s.names == [p["name"] for p in doc["parameters"]]
    assert list(s.lower) == [p["lower"] for p in doc["parameters"]]
    assert list(s.upper) == [p["upper"] for p in doc["parameters"]]
    assert s.log_scale == [p.get("log", False) for p in doc["parameters"]]
    scene = pronk.load_scene(study2_path.parent / doc["scene"]).resolved()
    assert s.initial[0] == scene["pulse"]["duration"]
    assert s.initial[3] == scene["controller"]["kp"][3]
    assert len(s.constraint_names) == 3 and s.scenarios == 16
    u = pronk.Study(study2_path, threads=1, unit=True)
    assert list(u.lower) == [0.0] * 11 and list(u.upper) == [1.0] * 11
    np.testing.assert_array_equal(u.initial, s.to_unit(s.initial))
    # log scale: the unit coordinate of the geometric mean of the bounds is 1/2
    i = s.names.index("kp_roll")
    x = s.initial.copy()
    x[i] = np.sqrt(s.lower[i] * s.upper[i])
    assert s.to_unit(x)[i] == pytest.approx(0.5, abs=1e-14)


def same(a, b):
    assert a[0] == b[0]
    assert a[1].tobytes() == b[1].tobytes()
    assert a[2] == b[2]


def test_evaluate_one_and_two_threads_identical(study2_path, design2):
    s1 = pronk.Study(study2_path, threads=1, unit=True)
    s2 = pronk.Study(study2_path, threads=2, unit=True)
    points = [s1.initial, np.array(design2["unit"]), np.full(11, 0.3)]
    for x in points:
        same(s1.evaluate(x), s2.evaluate(x))
    costs, cons, metrics = s2.evaluate_batch(points)
    assert costs.shape == (3,) and cons.shape == (3, 3)
    for i, x in enumerate(points):
        same((costs[i], cons[i], metrics[i]), s1.evaluate(x))
    costs1, _, _ = s1.evaluate_batch(points)
    assert costs1.tobytes() == costs.tobytes()


def test_physical_and_unit_coordinates_agree(study2_path, design2):
    phys = pronk.Study(study2_path, threads=2)
    unit = pronk.Study(study2_path, threads=2, unit=True)
    u = np.array(design2["unit"])
    same(phys.evaluate(phys.from_unit(u)), unit.evaluate(phys.to_unit(phys.from_unit(u))))
    full = unit.evaluate_full(u)
    assert full["ok"] and full["values"].tolist() == phys.from_unit(u).tolist()
    assert len(full["scenarios"]) == 16 and full["model"] == "pulse"
    # the mean of the per-scenario metric is the aggregate
    stab = [sc["metrics"]["stabilized"] for sc in full["scenarios"]]
    assert full["metrics"]["stabilized"] == pytest.approx(np.mean(stab), abs=1e-15)


def test_evaluate_reproduces_the_committed_design(study2_path, design2):
    # The committed design was recorded by another build: equal within reproduce's rtol.
    s = pronk.Study(study2_path, threads=2, unit=True)
    cost, g, metrics = s.evaluate(design2["unit"])
    assert cost == pytest.approx(design2["cost"], rel=1e-6)
    for k, v in design2["metrics"].items():
        assert metrics[k] == pytest.approx(v, rel=1e-6, abs=1e-12), k
    assert (g <= 1e-9).all() == design2["feasible"]
    val = s.validation()
    assert val.is_validation and val.scenarios == 64
    vcost, _, vmetrics = val.evaluate(design2["unit"])
    assert vcost == pytest.approx(design2["validation"]["cost"], rel=1e-6)
    assert vmetrics["stabilized"] == pytest.approx(design2["validation"]["metrics"]["stabilized"])


def test_reproduce_wraps_the_cli(source_dir, run_cli):
    path = source_dir / "results" / "study2_legged_pulse_duty50" / "design.json"
    rep = pronk.reproduce(path, threads=2)
    cli = run_cli("reproduce", path, "--threads", "1")
    assert rep["reproduced"] == (cli.returncode == 0)
    last = cli.stdout.strip().splitlines()[-1]
    assert len(rep["values"]) == int(last.split(" of ")[1].split()[0])
    assert {v["name"] for v in rep["values"]} >= {"cost", "validation cost", "stabilized"}
    # The committed design records its trials' decisions: 16 scenarios, 64 held out.
    assert rep["decisions_recorded"] and rep["decision_differences"] == []
    assert "0 of 80 trial decisions differ" in last
    assert all(v["tolerance"] >= 0 for v in rep["values"])
    with pytest.raises(pronk.InputError) as info:
        pronk.reproduce({"type": "something else"})
    assert info.value.pointer == "/type"
    # rtol, when given, is a finite number > 0 (a ValueError, as for any bad argument).
    for bad in (-1.0, 0.0, float("nan"), float("inf")):
        with pytest.raises(ValueError, match="rtol: expected a finite number > 0"):
            pronk.reproduce(path, rtol=bad)
    assert pronk.reproduce(path, threads=2, rtol=1e-9)["mode"] == "rtol"


def test_failed_point_is_data_and_bad_study_raises(study2_path):
    doc = json.loads(study2_path.read_text())
    doc["parameters"][0]["upper"] = 5.0  # pulse durations that make the stride impossible
    s = pronk.Study(doc, threads=1, base_dir=study2_path.parent)
    cost, g, _ = s.evaluate(s.upper)
    assert np.isfinite(cost) and np.isfinite(g).all()
    doc["objective"][0]["metric"] = "stabilised"
    with pytest.raises(pronk.InputError) as info:
        pronk.Study(doc, base_dir=study2_path.parent)
    assert info.value.pointer == "/objective/0/metric" and "stabilised" in info.value.found
    with pytest.raises(ValueError):
        pronk.Study(study2_path).evaluate([1.0, 2.0])
    with pytest.raises(pronk.InputError) as info:
        pronk.Study(study2_path, overrides={"/optimizer/max_evaluation": 3})
    assert info.value.pointer == "/optimizer/max_evaluation"


def test_staged_study_needs_a_stage(source_dir):
    path = source_dir / "studies" / "study3_full_model_running.json"
    with pytest.raises(pronk.InputError) as info:
        pronk.Study(path)
    assert info.value.pointer == "/stages"
    doc = json.loads(path.read_text())
    s = pronk.Study(path, stage=doc["stages"][0]["name"], threads=2)
    assert 0 < len(s.names) <= len(doc["parameters"])


def read_cells_csv(path):
    with open(path) as f:
        return list(csv.DictReader(f))


def test_run_map_equals_the_cli(source_dir, run_cli, tmp_path):
    path = source_dir / "studies" / "map_seed_duty.json"
    sets = ['/axes=[{"kind": "duty_cycle", "range": [0.2, 0.4], "count": 3}]',
            "/trials/count=3", "/trials/duration=4", '/boundary={"resolution": 0.02}']
    cli_args = ["map", path, "--out", tmp_path / "cli", "-q", "--threads", "2"]
    for s in sets:
        cli_args += ["--set", s]
    run_cli(*cli_args)
    m = pronk.run_map(path, threads=2, out=tmp_path / "py", overrides=sets, figures=False)
    assert m["status"] == "completed"
    rows = read_cells_csv(tmp_path / "cli" / "cells.csv")
    c = m["cells"]
    assert len(c["index"]) == len(rows) == 3
    for i, row in enumerate(rows):
        assert c["value0"][i] == float(row["duty_cycle"])
        assert c["fraction_impulse"][i] == float(row["stabilized_impulse"])
        assert c["fraction_pulse"][i] == float(row["stabilized_pulse"])
        assert c["spectral_radius"][i] == float(row["spectral_radius"])
        assert c["mean_duty"][i] == float(row["mean_duty"])
    assert (tmp_path / "py" / "cells.csv").read_bytes() == (tmp_path / "cli" / "cells.csv").read_bytes()
    cli_summary = json.loads((tmp_path / "cli" / "summary.json").read_text())
    assert m["summary"] == cli_summary
    row = cli_summary["boundary"]["rows"][0]
    assert m["boundaries"][0]["boundary"] == row["boundary"]
