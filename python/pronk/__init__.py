"""pronk from Python: simulate hopping robots and tune them with any optimizer.

    import pronk
    r = pronk.simulate("studies/scenes/case3_legged_pulse.json")
    r.status, r.metrics["mean_duty_cycle"], r.trajectory["z"]   # NumPy arrays by column

    study = pronk.Study("studies/study2_legged_pulse_duty50.json")
    cost, constraints, metrics = study.evaluate(study.initial)   # constraints <= 0 feasible

See docs/python.md.
"""
from ._pronk import (  # noqa: F401
    InputError,
    Result,
    Scene,
    Study,
    __version__,
    commit,
    load_scene,
    reproduce,
    run_map,
    simulate,
)

__all__ = ["InputError", "Result", "Scene", "Study", "load_scene", "simulate", "run_map",
           "reproduce", "read_design", "__version__", "commit"]


def read_design(path):
    """A design.json of `pronk optimize` as a dict (plain JSON reading; its "scene" is the
    tuned scene, fully resolved: pronk.simulate(design["scene"]) runs it)."""
    import json

    with open(path, encoding="utf-8") as f:
        return json.load(f)
