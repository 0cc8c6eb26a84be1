"""pronk.read_pareto: the front of a multi-objective study as NumPy arrays, the same numbers
as pareto.csv."""
import csv

import numpy as np

import pronk


def test_read_pareto_matches_pareto_csv(run_cli, source_dir, tmp_path):
    out = tmp_path / "moo"
    run_cli("optimize", source_dir / "studies" / "moo_impulse_example.json", "--out", out,
            "--threads", "2", "-q")
    p = pronk.read_pareto(str(out))
    n = len(p["evaluation"])
    assert n >= 1 and 0 <= p["knee"] < n
    assert p["objectives"].shape == (n, len(p["objective_names"])) == (n, 2)
    assert p["parameters"].shape == (n, len(p["parameter_names"]))
    assert p["constraints"].shape == (n, len(p["constraint_names"]))
    with open(out / "pareto.csv", newline="") as f:
        table = list(csv.DictReader(f))
    assert len(table) == n
    for k, r in enumerate(table):
        assert int(r["evaluation"]) == p["evaluation"][k]
        for j, name in enumerate(p["objective_names"]):
            assert p["objectives"][k, j] == float(r[name])
        for j, name in enumerate(p["parameter_names"]):
            assert p["parameters"][k, j] == float(r[name])
        assert p["validation_stabilized"][k] == float(r["validation_stabilized"])
        assert (int(r["knee"]) == 1) == (k == p["knee"])
    # A front: no design dominates another (every objective minimized).
    f = p["objectives"]
    for a in range(n):
        for b in range(n):
            assert not (np.all(f[a] <= f[b]) and np.any(f[a] < f[b]))
    # The archive's hypervolume never falls.
    assert np.all(np.diff(p["hypervolume"]) >= 0)
    assert pronk.read_pareto(str(out / "pareto.json"))["knee"] == p["knee"]
