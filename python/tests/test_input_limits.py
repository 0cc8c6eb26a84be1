"""The module's arguments at their limits: documents nested too deep or holding themselves
(the file readers' limits, not a crash), thread counts past the CLI's range, a reproduce
tolerance that is no tolerance, and robot scenes the loader refuses (too many samples, a
fixed step that skips flights, no gravity in the full model)."""
import math

import numpy as np
import pytest

import pronk

MAX_DEPTH = 128  # io::kMaxJsonDepth, the file readers' limit


def nested_list(depth):
    """`depth` lists, each the only element of the one around it."""
    x = []
    for _ in range(depth - 1):
        x = [x]
    return x


def test_a_50000_deep_list_is_input_error_not_a_crash():
    doc = {"name": "deep", "controller": {"kp": nested_list(50000)}}
    with pytest.raises(pronk.InputError) as e:
        pronk.simulate(doc)
    # The pointer stops where the limit is passed: /controller/kp, then list indices.
    # /controller is level 2, kp level 3: the 129th level is kp's 126th nested list.
    assert e.value.file == "<dict>"
    assert e.value.pointer == "/controller/kp" + "/0" * (MAX_DEPTH - 2)
    assert e.value.expected == "a value nested at most 128 levels deep"
    assert e.value.found == "more than 128 levels"


def test_nesting_at_the_limit_converts_one_more_level_does_not():
    # The document itself is level 1: 127 lists inside it are 128 levels, as a file may have.
    at_limit = {"name": "deep", "extra": nested_list(MAX_DEPTH - 1)}
    with pytest.raises(pronk.InputError) as e:
        pronk.load_scene(at_limit)
    assert e.value.pointer == "/extra"  # converted, then refused as an unknown key
    past = {"name": "deep", "extra": nested_list(MAX_DEPTH)}
    with pytest.raises(pronk.InputError) as e:
        pronk.load_scene(past)
    assert e.value.expected == "a value nested at most 128 levels deep"


def test_a_dict_that_contains_itself_is_input_error():
    doc = {"name": "loop", "controller": {}}
    doc["controller"]["again"] = doc
    with pytest.raises(pronk.InputError) as e:
        pronk.simulate(doc)
    assert e.value.pointer == "/controller/again"
    assert e.value.found == "a container that contains itself"
    lst = []
    lst.append(lst)
    with pytest.raises(pronk.InputError) as e:
        pronk.load_scene({"name": "loop", "initial": {"position": lst}})
    assert e.value.pointer == "/initial/position/0"


def test_one_object_used_twice_is_no_cycle():
    # A list shared by two keys is a tree in JSON (two copies): accepted.
    shared = [0.0, 0.0, 0.4]
    s = pronk.load_scene({"name": "shared", "initial": {"position": shared,
                                                        "velocity": [0.0, 0.0, 0.0]}})
    twice = pronk.load_scene({"name": "shared", "initial": {"position": shared},
                              "controller": {"setpoint": {"position": shared}}})
    assert s.resolved()["initial"]["position"] == shared
    assert twice.resolved()["controller"]["setpoint"]["position"] == shared


def test_deep_override_values_are_input_error():
    with pytest.raises(pronk.InputError) as e:
        pronk.load_scene({"name": "x"}, overrides={"/controller/kp": nested_list(50000)})
    assert e.value.file == "overrides"
    assert e.value.pointer == "/controller/kp" + "/0" * MAX_DEPTH


@pytest.mark.parametrize("threads", [10**6, 1025, 10**30, -1, True, 2.0, "2"])
def test_study_threads_past_the_cli_range_are_value_error(source_dir, threads):
    study = source_dir / "studies" / "study2_legged_pulse_duty50.json"
    with pytest.raises(ValueError) as e:
        pronk.Study(str(study), threads=threads)
    assert str(e.value) == f"threads: expected 0 (all cores) or 1 to 1024, found {threads!r}"


def test_threads_in_range_are_taken(source_dir):
    study = source_dir / "studies" / "study2_legged_pulse_duty50.json"
    assert pronk.Study(str(study), threads=3).threads == 3
    assert pronk.Study(str(study), threads=np.int64(2)).threads == 2
    assert 1 <= pronk.Study(str(study), threads=0).threads <= 1024


def test_map_and_reproduce_threads_are_checked_too(source_dir):
    with pytest.raises(ValueError, match="threads: expected 0"):
        pronk.run_map(str(source_dir / "studies" / "map_seed_duty.json"), threads=10**6)
    design = source_dir / "results" / "study2_legged_pulse_duty50" / "design.json"
    with pytest.raises(ValueError, match="threads: expected 0"):
        pronk.reproduce(str(design), threads=10**6)


@pytest.mark.parametrize("rtol", [-1.0, 0.0, math.nan, math.inf, -math.inf])
def test_reproduce_refuses_a_tolerance_that_is_none(source_dir, rtol):
    design = source_dir / "results" / "study2_legged_pulse_duty50" / "design.json"
    with pytest.raises(ValueError) as e:
        pronk.reproduce(str(design), rtol=rtol)
    assert str(e.value) == f"rtol: expected a finite number > 0, found {rtol!r}"
