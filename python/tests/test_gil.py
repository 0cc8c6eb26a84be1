"""The bindings release the GIL while C++ works, proved without timing. Each call below
runs on a worker thread with the module's GIL probe armed: right after it releases the GIL
the call parks in the probe until this (main) thread signals it. The main thread waits for
the call to park with the GIL released, and it can only come back from that wait, and then
signal, by taking the GIL: if the call still held it, the main thread would stay blocked
until the probe gives up after 60 s and reports "not released". No sleep, no clock, no
switch interval: the outcome does not depend on how the threads are scheduled."""
import threading

import pytest

import pronk
from pronk import _pronk


def gil_released_during(call):
    """Runs call() on a worker thread with the probe armed; returns (released, value)."""
    out, errors = [], []

    def worker():
        try:
            out.append(call())
        except BaseException as e:  # noqa: B902 (re-raised in the main thread)
            errors.append(e)

    _pronk._gil_probe_arm()
    t = threading.Thread(target=worker)
    t.start()
    reached = _pronk._gil_probe_wait_reached(60.0)
    _pronk._gil_probe_signal()
    t.join()
    if errors:
        raise errors[0]
    assert reached, "the call never reached the point after its GIL release"
    return _pronk._gil_probe_result(), out[0]


@pytest.fixture(scope="module")
def study2(source_dir):
    return pronk.Study(source_dir / "studies" / "study2_legged_pulse_duty50.json", threads=2)


def test_simulate_releases_the_gil(source_dir):
    path = source_dir / "studies" / "scenes" / "case2_legged_impulse.json"
    released, r = gil_released_during(lambda: pronk.simulate(path))
    assert released is True, "pronk.simulate held the GIL: the main thread could not run"
    assert r.status == pronk.simulate(path).status  # the parked run is an ordinary run


@pytest.mark.parametrize("method", ["evaluate", "evaluate_batch", "evaluate_full"])
def test_study_evaluations_release_the_gil(study2, method):
    x = study2.initial
    call = {"evaluate": lambda: study2.evaluate(x),
            "evaluate_batch": lambda: study2.evaluate_batch([x]),
            "evaluate_full": lambda: study2.evaluate_full(x)}[method]
    released, value = gil_released_during(call)
    assert released is True, f"Study.{method} held the GIL: the main thread could not run"
    expected = study2.evaluate(x)[0]
    cost = {"evaluate": lambda v: v[0], "evaluate_batch": lambda v: v[0][0],
            "evaluate_full": lambda v: v["cost"]}[method](value)
    assert cost == expected


def test_run_map_and_reproduce_release_the_gil(source_dir, tmp_path):
    path = source_dir / "studies" / "map_seed_duty.json"
    sets = ['/axes=[{"kind": "duty_cycle", "range": [0.2, 0.4], "count": 3}]',
            "/trials/count=3", "/trials/duration=4", '/boundary={"resolution": 0.02}']
    released, m = gil_released_during(
        lambda: pronk.run_map(path, threads=2, out=tmp_path, overrides=sets, figures=False))
    assert released is True, "pronk.run_map held the GIL: the main thread could not run"
    assert m["status"] == "completed"
    design = source_dir / "results" / "study2_legged_pulse_duty50" / "design.json"
    released, rep = gil_released_during(lambda: pronk.reproduce(design, threads=2))
    assert released is True, "pronk.reproduce held the GIL: the main thread could not run"
    assert {v["name"] for v in rep["values"]} >= {"cost", "stabilized"}
