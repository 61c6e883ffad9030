"""corsa.collect: a data-collection run (`corsa run --rig`) from Python."""

import os


def collect(scenario, rig, output, *, format="corsa", force=False, preview=False, dt=0.01,
            seed=0, params=None, controller=None, npc=None, duration=3600.0, models=(),
            entity_models=(), time_of_day=None, weather=None):
    """Runs the scenario with the sensor rig and writes a dataset folder, as `corsa run
    --rig RIG -o OUTPUT` does (docs/datasets.md); read it back with corsa.Dataset(output).

    format 'corsa' or 'kitti' (adds OUTPUT/kitti/); force replaces a previous dataset; preview
    writes the contact sheet and video; the other options as for corsa.Simulation. Returns
    {end_reason, sim_time, steps, captures, files, wall_time}. Ctrl-C ends the run after the
    capture in progress (the dataset says 'interrupted') and raises KeyboardInterrupt.
    """
    from . import _sensors

    return _sensors.collect(os.fspath(scenario), os.fspath(rig), os.fspath(output), format,
                            bool(force), bool(preview), float(dt), int(seed), params, controller,
                            npc, float(duration), [str(m) for m in models],
                            [str(m) for m in entity_models], time_of_day, weather)
