"""Control from outside: commands, external controllers, UserDefinedValueCondition values and
CustomCommandAction handlers as Python callables."""

import threading
import warnings

import pytest

import corsa
from conftest import EXTERNAL, ROOT


def quiet(path=EXTERNAL, **options):
    """A simulation of the fixture with a value for its UserDefinedValueCondition."""
    options.setdefault("values", {"ego_ready": False})
    return corsa.Simulation(path, **options)


def test_an_external_controller_of_the_scenario_is_driven_only_from_python():
    sim = quiet()
    assert sim.is_external("Ego") and not sim.is_external("Npc")
    sim.run()  # the story's SpeedAction at 1 s does not move Ego: it keeps Init's 10 m/s
    assert sim.state("Ego").speed == 10.0
    assert sim.state("Ego").x == pytest.approx(10.0 + 10.0 * sim.time)


def test_external_names_more_controllers():
    sim = quiet(ROOT / "tests/engine/fixtures/controller_acc.xosc", external=["Acc"])
    assert sim.is_external("Follower") and not sim.is_external("Lead")


def test_set_speed_applies_at_the_next_step_and_an_external_entity_holds_it():
    sim = quiet()
    sim.step()
    sim.set_speed("Ego", 14.0)
    sim.set_speed("Npc", 0.0)
    assert sim.state("Ego").speed == 10.0  # not yet
    sim.step()
    assert sim.state("Ego").speed == 14.0 and sim.state("Npc").speed == 0.0
    sim.step()
    assert sim.state("Ego").speed == 14.0  # held: its controller is external
    assert sim.state("Npc").speed == 20.0  # its own controller again


def test_set_pose_places_the_entity_on_its_lane():
    sim = quiet()
    sim.step()
    sim.set_pose("Ego", 300.0, -5.25, 0.0, speed=3.0)
    sim.step()
    ego = sim.state("Ego")
    assert (ego.x, ego.y, ego.speed, ego.lane) == (300.0, -5.25, 3.0, -2)
    assert ego.s == pytest.approx(300.0)


def test_set_controls_drive_the_vehicle_model():
    sim = quiet()
    sim.step()
    for _ in range(200):
        sim.set_controls("Ego", throttle=0.5, steering=0.02)
        sim.step()
    ego = sim.state("Ego")
    assert 15.0 < ego.speed < 20.0  # 2 s at about 5 m/s^2 from 10 m/s
    assert ego.h > 0.05  # turned left
    for _ in range(300):
        sim.set_controls("Ego", brake=1.0)
        sim.step()
    assert sim.state("Ego").speed == 0.0


def test_bad_commands_are_value_errors():
    sim = quiet()
    with pytest.raises(ValueError, match="throttle and brake must be between 0 and 1"):
        sim.set_controls("Ego", throttle=2.0)
    with pytest.raises(ValueError, match="finite"):
        sim.set_speed("Ego", float("nan"))
    with pytest.raises(ValueError, match="no entity 'Nobody'"):
        sim.set_speed("Nobody", 1.0)


def test_a_value_callable_triggers_the_condition():
    sim = corsa.Simulation(EXTERNAL, values={"ego_ready": lambda: sim.time >= 2.0})
    sim.run()
    start = [r for r in sim.log() if r["element"].endswith("NpcSlow")
             and r["transition"] == "startTransition"]
    assert [r["time"] for r in start] == [2.0]
    assert sim.state("Npc").speed == 5.0


def test_set_value_takes_plain_values_and_refuses_others():
    sim = corsa.Simulation(EXTERNAL)
    sim.set_value("ego_ready", "true")
    sim.step()
    sim.step()
    assert sim.element_state("S::A::NpcGroup::NpcM::NpcSlow") != "standbyState"
    with pytest.raises(TypeError, match="must be a bool, int, float or str"):
        sim.set_value("ego_ready", [1, 2])


def test_no_value_warns_once_with_the_location():
    sim = corsa.Simulation(EXTERNAL)
    with pytest.warns(corsa.CorsaWarning, match=r"external_control\.xosc:\d+: warning: "
                      r"UserDefinedValueCondition 'ego_ready' has no value"):
        sim.step()
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        sim.step()  # once only
    assert any("ego_ready" in w for w in sim.warnings)


def test_an_exception_in_a_callback_propagates_and_stops_the_simulation():
    def broken():
        raise KeyError("planner failed")

    sim = corsa.Simulation(EXTERNAL, values={"ego_ready": broken})
    with pytest.raises(KeyError, match="planner failed"):
        sim.step()
    with pytest.raises(RuntimeError, match="stopped at an error"):
        sim.step()


def test_custom_commands_reach_the_python_handler():
    sim = corsa.Simulation(ROOT / "tests/engine/fixtures/action_custom_command.xosc")
    calls = []
    sim.on_command("test:mark", lambda text: calls.append((sim.time, text)))
    sim.run()
    assert calls == [(0.0, "init"), (pytest.approx(1.01), "one")]
    with pytest.raises(TypeError, match="must be callable"):
        sim.on_command("test:mark", 3)


def test_a_handler_may_command_entities():
    sim = corsa.Simulation(ROOT / "tests/engine/fixtures/action_custom_command.xosc")
    sim.on_command("test:mark", lambda text: sim.set_speed("Car", 0.0))
    speeds = {}
    while sim.step():
        speeds[round(sim.time, 2)] = sim.state("Car").speed
    # The story's command comes at 1.01 s: the step it starts is the one the speed applies to;
    # then the default controller goes on at the scenario's 10 m/s. (Init's command comes before
    # time starts: the first step, to 0.01 s.)
    assert speeds[0.01] == 0.0 and speeds[0.02] == 10.0
    assert speeds[1.02] == 0.0 and speeds[1.03] == 10.0


def test_step_from_a_callback_of_the_same_step_is_refused():
    sim = corsa.Simulation(EXTERNAL, values={"ego_ready": lambda: sim.step()})
    with pytest.raises(RuntimeError, match="already stepping"):
        sim.step()


def test_another_thread_gets_an_error_while_one_steps():
    release = threading.Event()
    entered = threading.Event()

    def slow():
        entered.set()
        release.wait(5.0)
        return False

    sim = corsa.Simulation(EXTERNAL, values={"ego_ready": slow})
    worker = threading.Thread(target=sim.step)
    worker.start()
    entered.wait(5.0)
    try:
        with pytest.raises(RuntimeError, match="busy in another thread"):
            sim.state("Ego")
    finally:
        release.set()
        worker.join()
    assert sim.tick == 1
