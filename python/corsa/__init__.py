"""Corsa from Python: the scenario engine, control from outside, sensors and datasets.

    import corsa
    sim = corsa.Simulation("scenarios/cut_in.xosc", external=["Driver"])
    while sim.step():
        sim.set_speed("Ego", 20.0)
    frame = corsa.Dataset("out/dataset")[0]

The same library calls as the `corsa` command line (docs/python.md). `import corsa` loads the
engine only; the sensors (Embree, OpenCV, assimp, PROJ) load when a rig is first used, and
numpy when an array is first made.
"""

from ._corsa import CorsaWarning, EntityState, InputError, __version__
from ._simulation import Simulation
from ._batch import sweep, test
from ._trajectory import Trajectory, read_trajectory

__all__ = [
    "Simulation",
    "EntityState",
    "Dataset",
    "Frame",
    "TorchDataset",
    "collect",
    "sweep",
    "test",
    "read_trajectory",
    "Trajectory",
    "InputError",
    "CorsaWarning",
    "__version__",
]

# Loaded on first use (PEP 562): they import numpy, the sensor or the image extension.
_LAZY = {
    "Dataset": "._dataset",
    "Frame": "._frame",
    "TorchDataset": "._torch",
    "collect": "._collect",
}


def __getattr__(name):
    module = _LAZY.get(name)
    if module is None:
        raise AttributeError(f"module 'corsa' has no attribute '{name}'")
    import importlib

    value = getattr(importlib.import_module(module, __name__), name)
    globals()[name] = value
    return value


def __dir__():
    return sorted(set(globals()) | set(_LAZY))
