"""Bad input from Python: corsa.InputError with the command line's text and the location as
attributes; bad arguments are ValueError/TypeError; nothing crashes the interpreter."""

import subprocess
import sys
import textwrap

import pytest

import corsa
from conftest import CUT_IN, ROOT, environment


def test_a_missing_scenario_is_an_input_error_naming_it(tmp_path):
    missing = tmp_path / "nope.xosc"
    with pytest.raises(corsa.InputError) as caught:
        corsa.Simulation(missing)
    error = caught.value
    assert isinstance(error, ValueError)
    assert str(error) == f"{missing}: error: cannot open file (No such file or directory)"
    assert error.file == str(missing) and error.line is None
    assert error.message == "cannot open file (No such file or directory)"
    assert error.diagnostics[0]["text"] == str(error)


def test_an_error_in_the_scenario_carries_its_line():
    path = ROOT / "tests/engine/fixtures/error_missing_lane.xosc"
    with pytest.raises(corsa.InputError) as caught:
        corsa.Simulation(path)
    error = caught.value
    assert (error.file, error.line) == (str(path), 27)
    assert str(error) == f"{path}:27: error: road '1' has no lane -9 at s = 10"


def test_a_bad_parameter_value_is_located_as_on_the_command_line():
    with pytest.raises(corsa.InputError, match="CutInGap"):
        corsa.Simulation(CUT_IN, params={"CutInGap": "wide"})
    with pytest.raises(corsa.InputError, match="Nope"):
        corsa.Simulation(CUT_IN, params={"Nope": 1})


@pytest.mark.parametrize("options, error, text", [
    ({"dt": 0.0}, ValueError, "dt expects a step in seconds"),
    ({"dt": 20.0}, ValueError, "dt expects a step in seconds"),
    ({"duration": float("inf")}, ValueError, "duration expects a finite number"),
    ({"controller": "autopilot"}, ValueError, "controller expects 'default', 'acc' or 'dynamics'"),
    ({"npc": {"vehicles": -1}}, ValueError, r"npc\['vehicles'\] expects a count"),
    ({"npc": {"bikes": 2}}, ValueError, "unknown key 'bikes'"),
    ({"npc": "vehicles=3"}, TypeError, "npc expects a dict"),
    ({"params": {"CutInGap": [1]}}, TypeError, "must be a bool, int, float or str"),
    ({"external": "Driver"}, TypeError, "list of controller names"),
    ({"semantics": "sumo"}, ValueError, "semantics expects 'standard' or 'esmini'"),
    ({"models": ["a.obj"]}, ValueError, "are for a rig"),
])
def test_bad_arguments_are_refused_before_loading(options, error, text):
    with pytest.raises(error, match=text):
        corsa.Simulation(CUT_IN, **options)


def test_a_bad_rig_is_a_located_input_error(tmp_path):
    rig = tmp_path / "rig.xml"
    rig.write_text('<?xml version="1.0"?>\n<SensorRig version="1" name="r">\n'
                   '  <Lidar name="l" entity="Ego" channels="500"/>\n</SensorRig>\n')
    with pytest.raises(corsa.InputError) as caught:
        corsa.Simulation(CUT_IN, rig=rig)
    assert caught.value.line == 3 and "channels" in str(caught.value)
    rig.write_text('<?xml version="1.0"?>\n<SensorRig version="1" name="r">\n'
                   '  <Lidar name="l" entity="Nobody"/>\n</SensorRig>\n')
    with pytest.raises(corsa.InputError, match="'Nobody', which the scenario does not have"):
        corsa.Simulation(CUT_IN, rig=rig)


def test_broken_files_never_crash_the_interpreter(tmp_path):
    """Truncated and garbled scenarios, broken maps from the robustness corpus, folders and
    binary files: each is an InputError in a child interpreter, which exits normally."""
    text = CUT_IN.read_text()
    cases = []
    for cut in (0, 1, 40, 500, 2000, 5000, 8000):
        path = tmp_path / f"truncated_{cut}.xosc"
        path.write_text(text[:cut])
        cases.append(path)
    garbled = tmp_path / "garbled.xosc"
    garbled.write_bytes(bytes(range(256)) * 8)
    cases.append(garbled)
    for xodr in sorted((ROOT / "tests/robustness/corpus").glob("bad_*.xodr")):
        path = tmp_path / f"map_{xodr.stem}.xosc"
        path.write_text(text.replace('filepath="maps/motorway_2km.xodr"', f'filepath="{xodr}"'))
        cases.append(path)
    cases += [tmp_path, ROOT / "scenarios/maps/motorway_2km.xodr"]
    script = textwrap.dedent("""
        import sys, warnings
        import corsa
        warnings.simplefilter("ignore")
        for path in sys.argv[1:]:
            try:
                corsa.Simulation(path).run()
                print("ran", path)
            except corsa.InputError as error:
                assert error.file, path
                print("input error", path)
        """)
    child = subprocess.run([sys.executable, "-c", script, *map(str, cases)], capture_output=True,
                           text=True, env=environment(), timeout=300)
    assert child.returncode == 0, child.stderr
    lines = child.stdout.splitlines()
    assert len(lines) == len(cases)
    assert all(line.startswith("input error") for line in lines), lines


def test_warnings_are_corsa_warnings_with_the_command_line_text(tmp_path):
    scenario = tmp_path / "warn.xosc"
    # An entity that no Init action places waits at the origin, with a located warning.
    text = CUT_IN.read_text()
    start = text.index('<Private entityRef="Cutter">')
    end = text.index("</Private>", start) + len("</Private>")
    text = text[:start] + text[end:]
    # Written elsewhere, so its map and catalogs are named by absolute paths.
    text = text.replace('filepath="maps/', f'filepath="{ROOT}/scenarios/maps/')
    text = text.replace('<Directory path="catalogs"/>',
                        f'<Directory path="{ROOT}/scenarios/catalogs"/>')
    scenario.write_text(text)
    with pytest.warns(corsa.CorsaWarning, match=r"warn\.xosc:\d+: warning: entity 'Cutter' has "
                      r"no position in Init"):
        sim = corsa.Simulation(scenario)
    assert len(sim.warnings) == 1
