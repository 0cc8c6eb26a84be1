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
           "reproduce", "read_design", "read_sensitivity", "__version__", "commit"]


def read_design(path):
    """A design.json of `pronk optimize` as a dict (plain JSON reading; its "scene" is the
    tuned scene, fully resolved: pronk.simulate(design["scene"]) runs it)."""
    import json

    with open(path, encoding="utf-8") as f:
        return json.load(f)


def read_sensitivity(path):
    """The results of `pronk sensitivity` (its --out directory, or its sensitivity.json) as
    NumPy arrays, rows the outputs and columns the inputs (docs/sensitivity.md):

        s = pronk.read_sensitivity("sens1")
        s["elasticity"][s["outputs"].index("cost")]    # one row: the cost's elasticities
        s["ST"], s["ST_lo"], s["ST_hi"]                 # total Sobol indices, intervals

    Keys: "inputs", "outputs" (names), "pointers", "value", "lower", "upper" (per input),
    "f0" (per output), "derivative", "error", "elasticity", "at_lower", "at_upper", and with
    Sobol indices "S1", "S1_lo", "S1_hi", "ST", "ST_lo", "ST_hi" (outputs x inputs; NaN where
    the file has null), plus "document", the whole JSON."""
    import json
    import os

    import numpy as np

    if os.path.isdir(path):
        path = os.path.join(path, "sensitivity.json")
    with open(path, encoding="utf-8") as f:
        doc = json.load(f)
    inputs = [i["name"] for i in doc["inputs"]]
    outputs = list(doc["outputs"])
    col = {n: j for j, n in enumerate(inputs)}
    row = {n: i for i, n in enumerate(outputs)}

    def table(rows, keys):
        out = {k: np.full((len(outputs), len(inputs)), np.nan) for k in keys}
        for r in rows:
            for k in keys:
                if r[k] is not None:
                    out[k][row[r["output"]], col[r["input"]]] = r[k]
        return out

    res = {
        "inputs": inputs,
        "outputs": outputs,
        "pointers": [i["pointer"] for i in doc["inputs"]],
        "document": doc,
    }
    for k in ("value", "lower", "upper"):
        res[k] = np.array([i[k] for i in doc["inputs"]], dtype=float)
    values = doc["local"]["values"]
    res["f0"] = np.array([np.nan if values[o] is None else values[o] for o in outputs])
    res.update(table(doc["local"]["derivatives"],
                     ("derivative", "error", "elasticity", "at_lower", "at_upper")))
    if doc.get("sobol"):
        res.update(table(doc["sobol"]["indices"], ("S1", "S1_lo", "S1_hi", "ST", "ST_lo", "ST_hi")))
    return res
