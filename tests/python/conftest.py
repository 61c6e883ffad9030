"""Shared fixtures of the corsa Python module's tests (run by ctest: corsa_python_tests).

The module comes from PYTHONPATH (build/python); paths are relative to the repository root,
which is where ctest runs these tests.
"""

import os
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
SMALL_RIG = ROOT / "tests/collect/fixtures/small_rig.xml"
EXTERNAL = ROOT / "tests/engine/fixtures/external_control.xosc"
CUT_IN = ROOT / "scenarios/cut_in.xosc"


@pytest.fixture(scope="session")
def root():
    return ROOT


@pytest.fixture(scope="session")
def dataset(tmp_path_factory):
    """A small dataset of the bundled cut-in (every sensor kind, 0.5 s, with the KITTI export),
    written once by corsa.collect as `corsa run --rig` writes it."""
    import corsa

    folder = tmp_path_factory.mktemp("datasets") / "cut_in"
    corsa.collect(CUT_IN, SMALL_RIG, folder, format="kitti", duration=0.5)
    return folder


@pytest.fixture()
def in_root(monkeypatch):
    """Runs the test in the repository root (for relative paths as the docs write them)."""
    monkeypatch.chdir(ROOT)
    return ROOT


def environment():
    """The environment for a child interpreter: the same module path, no bytecode files."""
    env = dict(os.environ)
    env["PYTHONDONTWRITEBYTECODE"] = "1"
    # Absolute, for a child that runs in another folder.
    paths = env.get("PYTHONPATH", "").split(os.pathsep)
    env["PYTHONPATH"] = os.pathsep.join(os.path.abspath(p) for p in paths if p)
    return env
