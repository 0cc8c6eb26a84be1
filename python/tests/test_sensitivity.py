"""pronk.read_sensitivity: the files of `pronk sensitivity` as NumPy arrays, the same numbers
as local.csv and sobol.csv."""
import csv
import math

import numpy as np

import pronk


def test_read_sensitivity_matches_the_csv_files(run_cli, source_dir, tmp_path):
    design = source_dir / "results" / "study1_body_only_gains" / "design.json"
    out = tmp_path / "sens"
    run_cli("sensitivity", design, "--out", out, "--samples", "4", "--threads", "2", "-q")
    s = pronk.read_sensitivity(str(out))
    k, m = len(s["inputs"]), len(s["outputs"])
    assert "mass" in s["inputs"] and s["outputs"][0] == "cost"
    for key in ("derivative", "error", "elasticity", "at_lower", "at_upper", "S1", "ST_hi"):
        assert s[key].shape == (m, k)
    assert s["value"].shape == (k,) and s["f0"].shape == (m,)
    assert np.all(np.isfinite(s["elasticity"][0]))
    with open(out / "local.csv", newline="") as f:
        for r in csv.DictReader(f):
            i, j = s["outputs"].index(r["output"]), s["inputs"].index(r["input"])
            want = float(r["derivative"]) if r["derivative"] else math.nan
            assert s["derivative"][i, j] == want or (math.isnan(want) and math.isnan(s["derivative"][i, j]))
    with open(out / "sobol.csv", newline="") as f:
        for r in csv.DictReader(f):
            i, j = s["outputs"].index(r["output"]), s["inputs"].index(r["input"])
            if r["ST"]:
                assert s["ST"][i, j] == float(r["ST"])
    # The JSON file itself is accepted too.
    assert pronk.read_sensitivity(str(out / "sensitivity.json"))["inputs"] == s["inputs"]
