"""The examples of docs/python.md and the README run as written."""

import subprocess
import sys

from conftest import ROOT, environment


def test_the_closed_loop_example_drives_the_ego_and_reads_a_dataset_frame(tmp_path):
    # Run where the example's relative paths lead: scenarios/ of the repository, out/ here.
    (tmp_path / "scenarios").symlink_to(ROOT / "scenarios")
    child = subprocess.run([sys.executable, str(ROOT / "python/examples/closed_loop.py")],
                           cwd=tmp_path, capture_output=True, text=True, env=environment(),
                           timeout=300)
    assert child.returncode == 0, child.stderr
    run, arrays = child.stdout.splitlines()
    # The Python controller keeps 2 s behind the car that cuts in: no collision.
    assert run.startswith("0 collisions; Ego at ")
    assert "'front_rgb': ((180, 320, 3), '|u1')" in arrays
    assert "'front_depth': ((180, 320), '<f4')" in arrays
    assert (tmp_path / "out/py/frames.csv").exists()
