#!/usr/bin/env python3
"""The family table: per robot designed by `pronk design` (DIR/<robot>/design.json), the
held-out validation in the full model: stabilized, fell, apex held and hop-height error,
duty, cost of transport, and the pipeline's wall time; beside it, when NOMINAL_DIR/<robot>
holds the same robot tuned on the nominal robot only (`pronk design --tune-nominal`), that
design's stabilized and fell on the same perturbed trials. The wall time is the one
bench/family_pipeline.py measured with the robot alone on the machine (BENCH_JSON, default
results/bench/family_pipeline.json) when it made this very design; else the recording run's
own clock, marked.
    scripts/family_table.py RESULTS_DIR [NOMINAL_DIR] [BENCH_JSON]"""
import json
import pathlib
import sys


def nominal_cells(d: pathlib.Path) -> str:
    if d is None or not (d / "design.json").is_file():
        return "| - |"
    v = json.loads((d / "design.json").read_text())["validation"]["metrics"]
    return f"| {100 * v['stabilized']:.1f} % / {100 * v['fell']:.1f} % |"


def transport(v: dict, speed: list) -> str:
    # Work per weight per distance: a robot hopping in place covers only its drift, and the
    # number measures the drift, not the gait.
    if abs(speed[0]) + abs(speed[1]) == 0:
        return "- (hops in place)"
    return f"{v['cost_of_transport']:.2f}"


def wall_cell(design: dict, timed: dict) -> str:
    """The pipeline's own clock and the whole process, measured alone, when the bench made
    this same design; else the recording run's own clock (beside other work: marked)."""
    if timed and timed.get("same_as_committed"):
        return (f"{timed['own_clock_s'] / 60:.1f} min ({timed['process_wall_min']:.1f} "
                "whole process)")
    return f"{design['wall_time_s'] / 60:.1f} min (recording run, loaded)"


def row(d: pathlib.Path, nominal: pathlib.Path, timed: dict) -> str:
    design = json.loads((d / "design.json").read_text())
    v = design["validation"]["metrics"]
    scene = json.loads((d / "scene.json").read_text())
    body, legs, c = scene["body"], scene["legs"], scene["controller"]
    speed = c.get("setpoint", {}).get("velocity", [0, 0, 0])
    n = len(design["validation"]["trials"])
    robot = (f"{len(legs['hips'])} legs, {body['mass']:g} kg, h {c['hop_height']:g} m, "
             f"v ({speed[0]:g}, {speed[1]:g}) m/s")
    return (f"| {d.name} | {robot} | {n} | **{100 * v['stabilized']:.1f} %** | {100 * v['fell']:.1f} % "
            f"| {100 * v['apex_held']:.1f} % | {1000 * v['hop_height_error']:.1f} mm "
            f"| {v['duty_mean']:.3f} | {transport(v, speed)} "
            f"| {wall_cell(design, timed)} {nominal_cells(nominal)}")


def main() -> None:
    root = pathlib.Path(sys.argv[1])
    nominal_root = pathlib.Path(sys.argv[2]) if len(sys.argv) > 2 else None
    bench = pathlib.Path(sys.argv[3] if len(sys.argv) > 3 else
                         pathlib.Path(__file__).resolve().parent.parent / "results" / "bench" /
                         "family_pipeline.json")
    timed = {}
    if bench.is_file():
        timed = {r["robot"]: r for r in json.loads(bench.read_text())["robots"]}
    dirs = sorted(p for p in root.iterdir() if (p / "design.json").is_file())
    print("# The robot family, designed by `pronk design`\n")
    print("Each robot's scene gives only its body, legs and gait (studies/scenes/family/); "
          "`pronk design` derived and ran its study with the default options. Held-out "
          "validation trials in the full model, every trial disturbed (tilt <= 10 deg, lateral "
          "offset <= 0.2 m, kick <= 0.2 m/s) and the robot perturbed (mass +-15 %, inertia "
          "+-20 %, leg stiffness +-15 %, friction 0.6-1.2). The last column is the same robot "
          "tuned on the nominal robot only (`--tune-nominal`), validated on the same perturbed "
          "trials: the gap is what robust design buys.\n")
    print("| robot | body, legs, gait | trials | stabilized | fell | apex held (3 %) "
          "| hop-height error (RMS; a fall counts its penalty, 1-2 m) | duty | cost of transport "
          "| wall time: pipeline (whole process) | tuned nominal only: stabilized / fell |")
    print("| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |")
    for d in dirs:
        print(row(d, nominal_root / d.name if nominal_root else None, timed.get(d.name)))
    # Designs whose derived study ran at the scene default of the attitude trim's limit (the
    # command raised it to 0.4 rad later; those designs still reproduce as recorded).
    older = [d.name for d in dirs
             if not any("attitude_trim_max" in o for o in
                        json.loads((d / "study.json").read_text()).get("scene_overrides", []))]
    if older:
        print(f"\n{', '.join(older)}: designed before `pronk design` raised the attitude trim's "
              "limit to 0.4 rad (their studies run at the 0.2 rad default).")
    print("\nWall times: `bench/family_pipeline.py` on a 2-core machine, each robot alone, 2 "
          "threads, the figures rendered ([family_pipeline.json](../bench/family_pipeline.json)). "
          "The pipeline (pulse stage, full stage, validation) is the design's own clock; the whole "
          "process adds the reproduction record (every trial rerun 8 times from inputs perturbed "
          "by 1e-12, for `pronk reproduce` on other builds), the figures and the pages.")


if __name__ == "__main__":
    main()
