"""pronk.simulate against `pronk simulate` of the same build: the same numbers, bit for bit
(summary.json, trajectory.csv, strides.csv; energy.csv and feet.csv in the full model)."""
import json

import numpy as np
import pytest

import pronk


def read_csv(path):
    with open(path) as f:
        header = f.readline().strip().split(",")
    data = np.loadtxt(path, delimiter=",", skiprows=1, ndmin=2)  # %.17g reads back exactly
    return header, data.reshape(-1, len(header))


def assert_table_equal(table, path):
    header, data = read_csv(path)
    assert list(table) == header
    for i, name in enumerate(header):
        col = table[name]
        assert col.dtype == np.float64 and col.shape == (data.shape[0],)
        # Bit for bit (a byte comparison also tells -0.0 from 0.0).
        assert col.tobytes() == np.ascontiguousarray(data[:, i]).tobytes(), name


def without_wall_time(summary):
    s = json.loads(json.dumps(summary))
    del s["cost"]["wall_time_s"]
    return s


CASES = [
    ("case1_body_only.json", None, {}),
    ("case3_legged_pulse.json", None, {"/controller/hop_height": 0.25}),
    ("case2_legged_impulse.json", "pulse", {"/simulation/duration": 4}),
]


@pytest.mark.parametrize("scene,model,overrides", CASES)
def test_simulate_equals_cli_summary_bit_for_bit(source_dir, run_cli, tmp_path, scene, model,
                                                 overrides):
    path = source_dir / "studies" / "scenes" / scene
    args = ["simulate", path, "--out", tmp_path, "-q"]
    for k, v in overrides.items():
        args += ["--set", f"{k}={json.dumps(v)}"]
    if model:
        args += ["--model", model]
    run_cli(*args)
    r = pronk.simulate(str(path), model=model, overrides=overrides)
    cli = json.loads((tmp_path / "summary.json").read_text())
    assert without_wall_time(r.summary) == without_wall_time(cli)
    assert r.status == cli["status"] and r.reason == cli["reason"]
    assert r.metrics == cli["metrics"]
    assert r.t_end == cli["t_end"]
    assert_table_equal(r.trajectory, tmp_path / "trajectory.csv")
    assert_table_equal(r.strides, tmp_path / "strides.csv")
    assert r.energies is None and r.feet is None
    assert r.scene.resolved() == json.loads((tmp_path / "scene.resolved.json").read_text())


def test_full_model_energies_and_feet_equal_cli(source_dir, run_cli, tmp_path):
    path = source_dir / "studies" / "scenes" / "case5_pr_hop_height.json"
    overrides = ["/simulation/duration=0.6"]
    run_cli("simulate", path, "--out", tmp_path, "-q", "--set", overrides[0])
    r = pronk.simulate(pronk.load_scene(path), overrides=overrides)
    assert r.model == "pseudo_rigid"
    cli = json.loads((tmp_path / "summary.json").read_text())
    assert without_wall_time(r.summary) == without_wall_time(cli)
    assert "discrepancy_vs_pulse_model" in r.summary["pseudo_rigid"]
    assert_table_equal(r.trajectory, tmp_path / "trajectory.csv")
    assert_table_equal(r.strides, tmp_path / "strides.csv")
    assert_table_equal(r.energies, tmp_path / "energy.csv")
    assert_table_equal(r.feet, tmp_path / "feet.csv")
    # The energy balance column is the sum of its parts (energy.csv's definition).
    e = r.energies
    parts = e["kinetic"] + e["gravitational"] + e["internal"] + e["leg"] + e["contact"]
    np.testing.assert_allclose(e["balance"], parts + e["dissipated"] - e["actuator_work"],
                               rtol=1e-12, atol=1e-9)


def test_scene_object_dict_and_path_agree(source_dir):
    path = source_dir / "studies" / "scenes" / "case3_legged_pulse.json"
    doc = json.loads(path.read_text())
    from_path = pronk.simulate(pronk.load_scene(path))
    from_dict = pronk.simulate(doc)
    assert without_wall_time(from_path.summary) == without_wall_time(from_dict.summary)
    # A resolved scene simulates the same run (scene.resolved.json's promise).
    again = pronk.simulate(from_path.scene.resolved())
    assert again.trajectory["z"].tobytes() == from_path.trajectory["z"].tobytes()


def test_bad_input_raises_with_pointer_like_the_cli(source_dir, run_cli, tmp_path):
    doc = json.loads((source_dir / "studies" / "scenes" / "case3_legged_pulse.json").read_text())
    doc["controller"]["kpp"] = 1.0
    bad = tmp_path / "bad.json"
    bad.write_text(json.dumps(doc))
    with pytest.raises(pronk.InputError) as info:
        pronk.load_scene(bad)
    e = info.value
    assert isinstance(e, ValueError)
    assert (e.file, e.pointer) == (str(bad), "/controller/kpp")
    assert "known key" in e.expected and '"kpp"' in e.found
    cli = run_cli("simulate", bad, "--out", tmp_path / "out", check=False)
    assert cli.returncode == 2
    assert cli.stderr.strip() == f"pronk: error: {e}"


def test_bad_values_and_overrides_raise_with_pointer(source_dir):
    path = source_dir / "studies" / "scenes" / "case1_body_only.json"
    with pytest.raises(pronk.InputError) as info:
        pronk.simulate(path, overrides={"/body/mass": -1})
    assert info.value.pointer == "/body/mass" and info.value.found == "number -1"
    with pytest.raises(pronk.InputError) as info:
        pronk.load_scene({"body": {"inertia": [0.1, 0.1, 0.3]}})
    assert (info.value.file, info.value.pointer) == ("<dict>", "/body/inertia")
    with pytest.raises(pronk.InputError) as info:
        pronk.simulate(path, model="pseudo_rigid", overrides={"/pseudo_rigid/nonsense": 1})
    assert info.value.pointer.startswith("/pseudo_rigid")
    with pytest.raises(pronk.InputError):
        pronk.load_scene(path.parent / "does_not_exist.json")
