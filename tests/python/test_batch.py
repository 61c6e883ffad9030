"""corsa.sweep and corsa.test: the work of `corsa sweep` and `corsa test`, their tables as dicts."""

import csv
import os
import subprocess
from pathlib import Path

import pytest

import corsa
from conftest import ROOT

FOLLOW = ROOT / "tests/sweep/fixtures/follow.xosc"
GRID = ROOT / "tests/sweep/fixtures/grid.xosc"
# The command line to compare with (ctest passes the one it built).
CORSA = Path(os.environ.get("CORSA_BINARY", ROOT / "build/corsa"))


def test_a_distribution_file_gives_one_row_per_variant_in_index_order(tmp_path):
    rows = corsa.sweep(GRID, output=tmp_path / "grid", jobs=2, dt=0.02)
    assert [row["index"] for row in rows] == list(range(12))
    assert all(row["status"] == "ok" and row["exit_status"] == 0 for row in rows), rows
    # 3 speeds x 2 lanes x 2 (gap, lead speed) sets, the first varying slowest.
    assert [row["Ego_Speed"] for row in rows[::4]] == [20, 25, 30]
    assert {(row["Lane"], row["Gap"], row["Lead_Speed"]) for row in rows[:4]} == {
        (-2, 30, 10), (-2, 60, 20), (-3, 30, 10), (-3, 60, 20)}
    assert all(isinstance(row["steps"], int) and row["steps"] > 0 for row in rows)
    assert all(isinstance(row["sim_time"], float) for row in rows)
    assert (tmp_path / "grid/summary.csv").exists()


def test_a_grid_over_a_scenario_sweeps_the_named_parameters(tmp_path):
    rows = corsa.sweep(FOLLOW, {"Brake_Rate": [0.5, 4], "Gap": "30:40:10"},
                       output=tmp_path / "grid", jobs=1, dt=0.02)
    assert [(row["Brake_Rate"], row["Gap"]) for row in rows] == [
        (0.5, 30), (0.5, 40), (4, 30), (4, 40)]
    # Braking at 0.5 m/s^2 cannot avoid the slower lead; 4 m/s^2 can.
    assert [row["collisions"] > 0 for row in rows] == [True, True, False, False]


@pytest.mark.skipif(not CORSA.exists(), reason="needs the corsa command line in build/")
def test_the_summary_table_is_the_command_lines(tmp_path):
    corsa.sweep(GRID, output=tmp_path / "py", jobs=2, dt=0.02)
    subprocess.run([str(CORSA), "sweep", str(GRID), "-o", str(tmp_path / "cli"), "-j", "1",
                    "--dt", "0.02"], check=True, capture_output=True, timeout=120)

    def table(folder):
        with open(folder / "summary.csv", newline="") as f:
            rows = list(csv.DictReader(f))
        for row in rows:
            row.pop("wall_time", None)  # measured, not simulated
        return rows

    assert table(tmp_path / "py") == table(tmp_path / "cli")


def test_a_bad_sweep_is_a_located_input_error_before_anything_runs(tmp_path):
    with pytest.raises(corsa.InputError, match="Nope") as caught:
        corsa.sweep(FOLLOW, {"Nope": [1, 2]}, output=tmp_path / "bad")
    assert caught.value.file
    # A distribution parameter the scenario does not declare: left out with a located warning,
    # an error with strict=True.
    with pytest.warns(corsa.CorsaWarning, match="Wind_Speed' is not declared"):
        corsa.sweep(ROOT / "tests/sweep/fixtures/undeclared.xosc", output=tmp_path / "lenient")
    with pytest.raises(corsa.InputError) as caught:
        corsa.sweep(ROOT / "tests/sweep/fixtures/undeclared.xosc", output=tmp_path / "bad2",
                    strict=True)
    assert caught.value.file.endswith("undeclared.xosc") and caught.value.line
    with pytest.raises(ValueError, match="resume and force"):
        corsa.sweep(GRID, output=tmp_path / "x", resume=True, force=True)


def test_a_suite_gives_one_verdict_per_test_and_writes_its_junit_report(tmp_path):
    suite = tmp_path / "suite.xml"
    suite.write_text(f"""<?xml version="1.0" encoding="UTF-8"?>
<Suite version="1" name="python" dt="0.02">
  <Test name="calm" scenario="{FOLLOW}">
    <Expect endReason="stopTrigger" collision="false">
      <Metric name="max_deceleration" min="3.9" max="4.1"/>
    </Expect>
    <Golden every="20"/>
  </Test>
  <Test name="crash" scenario="{FOLLOW}" ego="Ego" duration="30">
    <Parameter name="Brake_Rate" value="0.5"/>
    <Expect collision="false"/>
  </Test>
</Suite>
""")
    first = corsa.test(suite, update_goldens=True, jobs=1)
    assert [t["name"] for t in first] == ["calm", "crash"]
    assert first[0]["golden_written"] is True
    junit = tmp_path / "report/junit.xml"
    outcomes = corsa.test(suite, junit=junit, jobs=2)
    calm, crash = outcomes
    assert calm["verdict"] == "PASS" and calm["passed"] and not calm["golden_written"]
    assert 3.9 <= calm["max_deceleration"] <= 4.1
    assert crash["verdict"] == "FAIL" and not crash["passed"]
    assert crash["collisions"] >= 1 and crash["failures"]
    text = junit.read_text()
    assert 'tests="2"' in text and 'failures="1"' in text


def test_a_missing_suite_is_an_input_error(tmp_path):
    with pytest.raises(corsa.InputError) as caught:
        corsa.test(tmp_path / "nope.xml")
    assert caught.value.file == str(tmp_path / "nope.xml")
