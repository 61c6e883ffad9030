"""corsa.Simulation: the engine's simulation (_corsa.Simulation) plus sensors in the loop."""

import os

from . import _corsa


class Simulation(_corsa.Simulation):
    """One run of one scenario, stepped from Python.

    Simulation(path, *, dt=0.01, seed=0, params=None, controller=None, npc=None, external=None,
               duration=3600.0, values=None, rig=None, models=(), entity_models=(),
               time_of_day=None, weather=None, semantics='standard')

    path         the .xosc scenario (its map and catalogs are found from it, as `corsa run` does)
    dt           the fixed step, s (0.0001..10)
    seed         run seed of every random draw
    params       {name: value} global parameter values (`--param`), checked against their types
    controller   'default', 'acc' or 'dynamics' for every vehicle the scenario gives none
    npc          {'vehicles': N, 'pedestrians': M} seeded random traffic (`--npc`)
    external     controller names whose entities are driven only from Python (besides any
                 'ExternalController' of the scenario)
    duration     cap on simulated time, s
    values       {name: value or callable} for UserDefinedValueConditions (see set_value)
    rig          a sensor rig file: capture() then renders its sensors (loads the sensor library)
    models       building models for the rig's scene, 'FILE[@X,Y[,HEADING_DEG]]' (`--model`)
    entity_models  models for entities, 'WHO=FILE': WHO an entity's name or a category such
                 as car or pedestrian (`--entity-model`); they win over the rig's <EntityModel>s
    time_of_day  'HH:MM[:SS]' for the rig's lighting (`--time-of-day`)
    weather      'fog=50,rain=0.6,...' for the rig's sensors (`--weather`)
    semantics    'standard' or 'esmini': where the standard's text and esmini differ (`--semantics`)

    Bad input raises corsa.InputError with the command line's 'file:line: error: message'.
    """

    def __init__(self, path, *, dt=0.01, seed=0, params=None, controller=None, npc=None,
                 external=None, duration=3600.0, values=None, rig=None, models=(),
                 entity_models=(), time_of_day=None, weather=None, semantics="standard"):
        super().__init__(os.fspath(path), dt=dt, seed=seed, params=params, controller=controller,
                         npc=npc, external=external, duration=duration, values=values,
                         semantics=semantics)
        self._sensors = None
        if rig is None:
            if models or entity_models or time_of_day is not None or weather is not None:
                raise ValueError(
                    "models, entity_models, time_of_day and weather are for a rig: pass rig=...")
            return
        from . import _sensors

        self._sensors = _sensors.SensorSession(self, os.fspath(rig), [str(m) for m in models],
                                               [str(m) for m in entity_models], time_of_day,
                                               weather)

    @property
    def sensors(self):
        """The rig's sensors as (name, kind, entity, rate in Hz) tuples; [] without a rig."""
        return [] if self._sensors is None else self._sensors.sensors

    def capture(self, sensors=None):
        """Renders the rig's sensors (all, or those named) at the current state, in memory.

        Returns a corsa.Frame: frame.data maps each sensor to a numpy array (RGB uint8 HxWx3,
        depth float32 HxW in metres, semantic and instance uint16 HxW, LiDAR a structured array
        with x, y, z, intensity, ring, class, instance, time), frame.labels its labels (dicts, as
        a dataset's _labels.json), frame.poses its world_from_sensor 4x4 matrix, frame.calibration
        its calibration, frame.entities every entity's pose and box. Sensor rates and capture
        windows are for datasets; capture() renders whenever it is called.
        """
        if self._sensors is None:
            raise ValueError("this simulation has no rig: corsa.Simulation(..., rig='rig.xml')")
        from ._frame import Frame

        names = [] if sensors is None else [sensors] if isinstance(sensors, str) else list(sensors)
        return Frame(**self._sensors.capture(names))
