"""The full model's stance-time estimate (the placement plans the next stance with the last
one measured) is not fooled by a foot's brief tap: a tripod landing tilted used to measure a
2 ms "stance", put its feet under its hips, and lurch forward 1.8 N s against 0.01 asked
until it fell."""
import json

import pytest

import pronk

# The tripod's full-stage design as `pronk design` tuned it before the fix (one of its 32
# perturbed held-out trials, number 22, fell at 1.76 s from exactly that lurch).
TRIPOD_BEFORE = {
    "attitude_trim_gain": 1.0095271777388304, "bank_kd": 0.0508210247676378,
    "bank_kp": 0.010966229005224901, "hop_trim_gain": 0.502853165270334,
    "kd_pitch": 0.009692651079075963, "kd_roll": 0.003653173329829497,
    "kd_x": 1.0912564941022065, "kd_y": 1.9979969513051756, "kp_pitch": 0.007018768045620313,
    "kp_roll": 0.011885165251601928, "kp_x": 0.9525659674924473, "kp_y": 1.3732182966954614,
    "leg_damping": 4.20520645555055, "leg_stiffness": 334.2355526710245,
    "position_trim_gain": 0.18179245894055282, "stance_kd_pitch": 8.296260502415498,
    "stance_kd_roll": 4.7818216696202995, "stance_kp_pitch": 10.953176264214145,
    "stance_kp_roll": 0.0,
}


def test_a_foot_tap_is_not_a_stance(tmp_path, run_cli, source_dir):
    out = tmp_path / "tripod"
    run_cli("design", source_dir / "studies/scenes/family/tripod.json", "--study-only",
            "--out", out, "-q")
    study = pronk.Study(out / "study.json", stage="full", threads=1, base_dir=out,
                        overrides={"/validation/random/count": 23})
    x = [TRIPOD_BEFORE[n] for n in study.names]
    trial = study.validation().evaluate_full(x)["scenarios"][22]
    assert trial["status"] == "completed", trial["reason"]
    # Nothing threw it forward (the lurch took it 0.5 m ahead): over the 10 s it stays within
    # a few cm of its moving setpoint, and ends within 2 cm of it.
    assert trial["metrics"]["x_error"] < 0.08
    assert trial["metrics"]["final_error"] < 0.02
