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
           "reproduce", "read_design", "read_sensitivity", "read_pareto", "__version__", "commit"]


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


def read_pareto(path):
    """The front of a multi-objective study (`pronk optimize` with "objectives": its output
    directory, or its pareto.json) as NumPy arrays, one row per non-dominated design
    (docs/pareto.md):

        p = pronk.read_pareto("results/study6_pareto_full_model")
        p["objectives"][:, p["objective_names"].index("cost_of_transport")]
        p["parameters"][p["knee"]]          # the knee design's parameter values

    Keys: "objective_names", "parameter_names", "constraint_names" (lists); "objectives"
    (designs x objectives), "parameters" (designs x parameters), "constraints" (designs x
    constraints), "evaluation" (each design's index in the journal), "validation_stabilized"
    and "validation_fell" (per design; NaN without a validation set); "knee" (a row index, -1
    for an empty front); "hypervolume" (per generation, the first population first),
    "reference" (the hypervolume's reference point); and "document", the whole JSON."""
    import json
    import os

    import numpy as np

    if os.path.isdir(path):
        path = os.path.join(path, "pareto.json")
    with open(path, encoding="utf-8") as f:
        doc = json.load(f)
    if doc.get("type") != "pronk_pareto":
        raise ValueError(f"{path}: expected a pareto.json of pronk (\"type\": \"pronk_pareto\")")
    front = doc["front"]
    onames, pnames = list(doc["objective_names"]), list(doc["parameter_names"])
    cnames = list(doc.get("constraint_names", []))

    def rows(get, width):
        return np.array([get(d) for d in front], dtype=float).reshape(len(front), width)

    def validation(d, key):
        v = d.get("validation")
        return np.nan if not v else v[key]

    return {
        "objective_names": onames,
        "parameter_names": pnames,
        "constraint_names": cnames,
        "objectives": rows(lambda d: [d["objectives"][n] for n in onames], len(onames)),
        "parameters": rows(lambda d: [d["parameters"][n] for n in pnames], len(pnames)),
        "constraints": rows(lambda d: d["constraints"], len(cnames)),
        "evaluation": np.array([d["evaluation"] for d in front], dtype=int),
        "validation_stabilized": np.array([validation(d, "stabilized") for d in front], dtype=float),
        "validation_fell": np.array([validation(d, "fell") for d in front], dtype=float),
        "knee": int(doc.get("knee", -1)),
        "hypervolume": np.array(doc.get("hypervolume", []), dtype=float),
        "reference": np.array(doc.get("reference", []), dtype=float),
        "document": doc,
    }
