"""corsa.read_trajectory: a binary trajectory (`corsa run --record FILE.corsatraj`) as numpy."""

import os

from . import _corsa


class Trajectory:
    """Every recorded row of a run: the trajectory CSV's numbers in one structured array.

    rows       numpy structured array, one row per present entity per recorded tick, in tick and
               then entity order: tick, time (s), entity (index into `entities`), x, y, z (m, map
               frame), h, p, r (rad), speed (m/s), on_road, road (index into `roads`), lane, s,
               t (m; meaningful where on_road)
    entities   entity names in document order; roads: OpenDRIVE road ids
    dt         the run's step (s); every: one tick in `every` was recorded (and the last)
    """

    def __init__(self, data):
        self.rows = data["rows"]
        self.entities = list(data["entities"])
        self.roads = list(data["roads"])
        self.dt = data["dt"]
        self.every = data["every"]

    def __len__(self):
        return len(self.rows)

    def of(self, name):
        """The rows of one entity (a copy), in tick order."""
        try:
            index = self.entities.index(name)
        except ValueError:
            raise ValueError(f"no entity '{name}' (entities: {', '.join(self.entities)})") from None
        return self.rows[self.rows["entity"] == index]

    def __repr__(self):
        return (f"<corsa.Trajectory {len(self.rows)} rows, {len(self.entities)} entities, "
                f"dt={self.dt:g} s>")


def read_trajectory(path):
    """Reads a binary trajectory; a damaged or foreign file is a corsa.InputError naming it."""
    return Trajectory(_corsa._read_trajectory(os.fspath(path)))
