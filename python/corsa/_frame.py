"""corsa.Frame: one capture of a rig, from Simulation.capture() or a Dataset."""


class Frame:
    """One capture: every sensor captured at one tick.

    data         {sensor: numpy array} (docs/python.md, "Arrays")
    labels       {sensor: dict} (cameras and LiDAR): the dataset's _labels.json, whose 'objects'
                 lists the labelled objects (docs/sensors.md, "Labels")
    poses        {sensor: 4x4 numpy array}, world_from_sensor (sensor body frame to map)
    calibration  {sensor: dict} (as the dataset's calibration.json; KITTI: the calib matrices)
    entities     [dict, ...] every entity: instance_id, name, category, pose [x y z h p r],
                 box [cx cy cz length width height], speed, velocity, yaw_rate, visible
    tick, time   when (engine tick, seconds; None in a KITTI folder); index: the capture's number
                 in a dataset

    frame["cam"] is frame.data["cam"]; iterating a frame gives its sensor names.
    """

    __slots__ = ("index", "tick", "time", "data", "labels", "poses", "calibration", "entities")

    def __init__(self, tick, time, data, labels=None, poses=None, calibration=None,
                 entities=None, index=None):
        self.index = index
        self.tick = tick
        self.time = time
        self.data = data
        self.labels = {} if labels is None else labels
        self.poses = {} if poses is None else poses
        self.calibration = {} if calibration is None else calibration
        self.entities = [] if entities is None else entities

    def __getitem__(self, sensor):
        return self.data[sensor]

    def __contains__(self, sensor):
        return sensor in self.data

    def __iter__(self):
        return iter(self.data)

    def __len__(self):
        return len(self.data)

    def keys(self):
        return self.data.keys()

    def __repr__(self):
        shapes = ", ".join(f"{name}: {getattr(array, 'shape', '?')}"
                           for name, array in self.data.items())
        where = "" if self.index is None else f"#{self.index} "
        when = "" if self.time is None else f"t={self.time:g} s "
        return f"<corsa.Frame {where}{when}{{{shapes}}}>"
