"""corsa.Simulation: stepping, the state of the run, the storyboard, the summary."""

import csv
import math

import numpy as np
import pytest

import corsa
from conftest import CUT_IN, EXTERNAL, ROOT


def test_stepping_reproduces_the_command_line_golden_trajectory():
    # scenarios/goldens/cut_in.csv is what `corsa run --record-every 10` writes; stepping from
    # Python must give the same states at the same ticks.
    with open(ROOT / "scenarios/goldens/cut_in.csv", newline="") as f:
        golden = list(csv.DictReader(f))
    rows = {(round(float(r["time"]) * 100), r["entity"]): r for r in golden}
    sim = corsa.Simulation(CUT_IN)
    compared = 0
    while True:
        for name in sim.entities:
            row = rows.get((sim.tick, name))
            if row is None:
                continue
            state = sim.state(name)
            assert state.x == pytest.approx(float(row["x"]), abs=1e-5)
            assert state.y == pytest.approx(float(row["y"]), abs=1e-5)
            assert state.h == pytest.approx(float(row["h"]), abs=1e-8)
            assert state.speed == pytest.approx(float(row["speed"]), abs=1e-5)
            assert state.road == row["road"]
            assert state.lane == int(row["lane"])
            compared += 1
        if not sim.step():
            break
    assert compared == len(golden)
    assert sim.ended and sim.end_reason == "stop trigger"
    assert sim.time == pytest.approx(21.76)


def test_step_returns_false_once_the_run_has_ended():
    sim = corsa.Simulation(CUT_IN, duration=0.05)
    assert [sim.step() for _ in range(7)] == [True] * 5 + [False, False]
    assert sim.tick == 5 and sim.end_reason == "duration"


def test_states_is_a_structured_array_matching_state():
    sim = corsa.Simulation(CUT_IN)
    for _ in range(300):
        sim.step()
    states = sim.states()
    assert states.dtype.names == ("x", "y", "z", "h", "p", "r", "speed", "acceleration", "road",
                                  "lane", "s", "t", "present")
    assert len(states) == len(sim.entities) == 2
    for row, name in zip(states, sim.entities):
        state = sim.state(name)
        assert (row["x"], row["y"], row["h"], row["speed"]) == (state.x, state.y, state.h,
                                                                 state.speed)
        assert (row["road"], row["lane"], row["s"], row["t"]) == (state.road, state.lane,
                                                                  state.s, state.t)
        assert row["present"]
    # A copy, not a view of the engine: later steps do not change it.
    x = states["x"].copy()
    sim.step()
    assert np.array_equal(states["x"], x)


def test_an_entity_off_every_lane_has_no_road_coordinates():
    sim = corsa.Simulation(EXTERNAL, external=["ExternalController"])
    sim.step()
    sim.set_pose("Ego", 100.0, 50.0, 0.0)  # 50 m beside the road
    sim.step()
    state = sim.state("Ego")
    assert state.road is None and state.lane is None and state.s is None
    row = sim.states()[sim.entities.index("Ego")]
    assert row["road"] == "" and row["lane"] == 0 and math.isnan(row["s"])


def test_run_returns_the_summary_the_command_line_writes():
    sim = corsa.Simulation(CUT_IN, seed=7)
    summary = sim.run()
    assert summary["end_reason"] == "stop trigger"
    assert summary["steps"] == 2176 and summary["seed"] == 7
    assert [e["name"] for e in summary["entities"]] == ["Ego", "Cutter"]
    assert summary["collisions"] == []
    assert summary["parameters"] == {"EgoSpeed": "27.78", "CutterSpeed": "33.33", "CutInGap": "10"}
    assert not sim.step()


def test_parameters_override_declared_values():
    sim = corsa.Simulation(CUT_IN, params={"CutInGap": 8, "EgoSpeed": 25.5})
    assert sim.parameters["CutInGap"] == 8.0
    assert sim.state("Ego").speed == 25.5


def test_storyboard_states_and_the_event_log():
    sim = corsa.Simulation(CUT_IN)
    elements = sim.elements()
    assert list(elements)[0] == ""  # the storyboard first
    assert all(state == "standbyState" for state in elements.values())
    sim.run()
    log = sim.log()
    assert log[0] == {"time": 0.0, "tick": 0, "type": "storyboard", "element": "",
                      "transition": "startTransition", "state": "runningState"}
    assert log[-1]["type"] == "storyboard" and log[-1]["state"] == "completeState"
    events = [r for r in log if r["type"] == "event" and r["transition"] == "startTransition"]
    assert events and all(r["element"] in sim.elements() for r in events)
    for path, state in sim.elements().items():
        assert sim.element_state(path) == state
    assert sim.element_state("NoSuchStory") is None


def test_collisions_are_records_with_both_entities():
    sim = corsa.Simulation(ROOT / "scenarios/suites/regression/stalled_car.xosc")
    sim.run()
    collisions = sim.collisions()
    assert len(collisions) == 1
    assert set(collisions[0]["entities"]) == {"Ego", "Stalled"}
    assert 4.0 < collisions[0]["time"] < 5.0


def test_unknown_entity_names_the_entities():
    sim = corsa.Simulation(CUT_IN)
    with pytest.raises(ValueError, match=r"no entity 'Nobody' \(entities: Ego, Cutter\)"):
        sim.state("Nobody")


def test_npc_and_controller_options_reach_the_engine():
    sim = corsa.Simulation(CUT_IN, npc={"vehicles": 3, "pedestrians": 0}, controller="acc",
                           seed=4)
    assert sim.entities[:2] == ("Ego", "Cutter")
    assert [n for n in sim.entities if n.startswith("npc_vehicle_")] == [
        "npc_vehicle_0", "npc_vehicle_1", "npc_vehicle_2"]
    other = corsa.Simulation(CUT_IN, npc={"vehicles": 3}, controller="acc", seed=4)
    assert np.array_equal(sim.states(), other.states())


def test_two_simulations_do_not_see_each_other():
    a = corsa.Simulation(CUT_IN)
    b = corsa.Simulation(CUT_IN)
    for _ in range(100):
        a.step()
    assert b.time == 0.0 and a.time == pytest.approx(1.0)
    assert b.state("Ego").x == 100.0


def test_the_esmini_reading_reaches_the_engine():
    # From 10 m/s a linear speed-up to 20 m/s in 2 s from 1 s on, beyond the car's Performance
    # (2 m/s^2, 15 m/s): exactly as written under the standard reading, 20 m/s at 4 s; esmini
    # holds it to the Performance, 15 m/s.
    path = ROOT / "tests" / "engine" / "fixtures" / "semantics_performance.xosc"
    standard = corsa.Simulation(path)
    esmini = corsa.Simulation(path, semantics="esmini")
    for sim in (standard, esmini):
        while sim.time < 4.0 - 1e-9:
            sim.step()
    assert standard.state("Car").speed == pytest.approx(20.0, abs=1e-9)
    assert esmini.state("Car").speed == pytest.approx(15.0, abs=1e-9)


def test_a_ghost_run_starts_at_its_negative_head_start_everywhere():
    # esmini's followGhost: the run starts 2 s early; time, tick, the log and the summary agree.
    sim = corsa.Simulation(ROOT / "tests/engine/fixtures/controller_follow_ghost.xosc")
    assert sim.start_time == pytest.approx(-2.0)
    assert sim.tick == -200 and sim.time == pytest.approx(-2.0) and sim.steps == 0
    assert sim.entities[-1] == "Ego_ghost"
    summary = sim.run()
    assert sim.tick == 1500 and sim.steps == 1700
    assert summary["steps"] == 1700 and summary["start_time"] == pytest.approx(-2.0)
    first = sim.log()[0]
    assert first["tick"] < 0 and first["time"] == pytest.approx(first["tick"] * sim.dt)
