"""corsa.read_trajectory: the binary trajectory of `corsa run --record FILE.corsatraj` as numpy."""

import csv
import os
import subprocess
from pathlib import Path

import numpy as np
import pytest

import corsa
from conftest import CUT_IN, ROOT

CORSA = Path(os.environ.get("CORSA_BINARY", ROOT / "build/corsa"))


@pytest.mark.skipif(not CORSA.exists(), reason="needs the corsa command line in build/")
def test_the_binary_trajectory_holds_the_numbers_of_the_csv(tmp_path):
    for name in ("run.corsatraj", "run.csv"):
        subprocess.run([str(CORSA), "run", str(CUT_IN), "--record", str(tmp_path / name),
                        "--record-every", "10", "--quiet"], check=True, capture_output=True,
                       timeout=120)
    trajectory = corsa.read_trajectory(tmp_path / "run.corsatraj")
    with open(tmp_path / "run.csv", newline="") as f:
        expected = list(csv.DictReader(f))
    assert trajectory.entities == ["Ego", "Cutter"] and trajectory.dt == 0.01
    assert trajectory.every == 10 and len(trajectory) == len(expected)
    rows = trajectory.rows
    for row, want in zip(rows, expected):
        assert trajectory.entities[row["entity"]] == want["entity"]
        assert row["time"] == pytest.approx(float(want["time"]), abs=1e-9)
        # The same doubles as parsing the CSV's decimals.
        assert (row["x"], row["y"], row["h"], row["speed"]) == (
            float(want["x"]), float(want["y"]), float(want["h"]), float(want["speed"]))
        assert row["on_road"] == (want["road"] != "")
        if row["on_road"]:
            assert trajectory.roads[row["road"]] == want["road"]
            assert (row["lane"], row["s"]) == (int(want["lane"]), float(want["s"]))
    ego = trajectory.of("Ego")
    assert np.all(np.diff(ego["tick"]) > 0) and len(ego) == len(rows) // 2
    with pytest.raises(ValueError, match="no entity 'Nobody'"):
        trajectory.of("Nobody")


def test_a_file_that_is_no_trajectory_is_an_input_error(tmp_path):
    path = tmp_path / "broken.corsatraj"
    path.write_bytes(b"CORSA" + bytes(100))
    with pytest.raises(corsa.InputError) as caught:
        corsa.read_trajectory(path)
    assert caught.value.file == str(path)
    with pytest.raises(corsa.InputError):
        corsa.read_trajectory(tmp_path / "missing.corsatraj")
