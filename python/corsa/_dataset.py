"""corsa.Dataset: the frames of a dataset folder (Corsa layout or KITTI) as numpy arrays."""

import csv
import json
import os
from pathlib import Path

import numpy as np

from ._errors import input_error
from ._frame import Frame

# One LiDAR return, as Simulation.capture() gives it (docs/python.md, "Arrays").
LIDAR_DTYPE = np.dtype({
    "names": ["x", "y", "z", "intensity", "ring", "class", "instance", "time"],
    "formats": ["<f4", "<f4", "<f4", "<f4", "<u2", "<u2", "<u4", "<f8"],
    "offsets": [0, 4, 8, 12, 16, 18, 20, 24],
    "itemsize": 32,
})

_PCD_TYPES = {("F", 4): "<f4", ("F", 8): "<f8", ("U", 1): "u1", ("U", 2): "<u2", ("U", 4): "<u4",
              ("I", 1): "i1", ("I", 2): "<i2", ("I", 4): "<i4"}


def _images():
    from . import _images

    return _images


def read_pcd(path, time=0.0):
    """A binary PCD point cloud as written by Corsa (x y z intensity ring label instance)."""
    data = Path(path).read_bytes()
    header = {}
    offset = 0
    while True:
        end = data.find(b"\n", offset)
        if end < 0:
            raise input_error(path, "PCD header without a DATA line")
        line = data[offset:end].decode("ascii", "replace").strip()
        offset = end + 1
        if not line or line.startswith("#"):
            continue
        key, _, value = line.partition(" ")
        header[key] = value.split()
        if key == "DATA":
            break
    if header.get("DATA") != ["binary"]:
        raise input_error(path, f"PCD data '{' '.join(header.get('DATA', []))}' is not binary")
    try:
        fields = header["FIELDS"]
        types = [_PCD_TYPES[(t, int(s))] for t, s in zip(header["TYPE"], header["SIZE"])]
        points = int(header["POINTS"][0])
        raw = np.frombuffer(data, dtype=np.dtype(list(zip(fields, types))), count=points,
                            offset=offset)
    except (KeyError, ValueError, IndexError) as error:
        raise input_error(path, f"not a PCD point cloud Corsa reads ({error})") from None
    out = np.zeros(points, dtype=LIDAR_DTYPE)
    for name, source in (("x", "x"), ("y", "y"), ("z", "z"), ("intensity", "intensity"),
                         ("ring", "ring"), ("class", "label"), ("instance", "instance")):
        if source in raw.dtype.names:
            out[name] = raw[source]
    out["time"] = time
    return out


def _read_json(path):
    try:
        with open(path, encoding="utf-8") as f:
            return json.load(f)
    except OSError as error:
        raise input_error(path, f"cannot read ({error.strerror})") from None
    except json.JSONDecodeError as error:
        raise input_error(path, f"not JSON: {error.msg}", error.lineno) from None


class _CorsaLayout:
    """DIR/frames.csv, DIR/run.json, DIR/poses/, DIR/<sensor>/ (docs/datasets.md)."""

    def __init__(self, folder):
        self.folder = folder
        self.run = _read_json(folder / "run.json")
        self.kinds = {s["name"]: s["kind"] for s in self.run.get("sensors", [])}
        self.captures = []  # [(capture, tick, time, [(sensor, frame, file), ...])]
        index = folder / "frames.csv"
        try:
            with open(index, newline="", encoding="utf-8") as f:
                rows = list(csv.reader(f))
        except OSError as error:
            raise input_error(index, f"cannot read ({error.strerror})") from None
        columns = ["capture", "tick", "time", "sensor", "frame", "file"]
        # Datasets since the overlap flag have a seventh column (entity pairs interpenetrating).
        if not rows or rows[0] not in (columns, columns + ["overlap"]):
            raise input_error(index, "not a Corsa frame index (header "
                              "capture,tick,time,sensor,frame,file[,overlap])", 1)
        width = len(rows[0])
        by_capture = {}
        for line, row in enumerate(rows[1:], start=2):
            try:
                if len(row) != width:
                    raise ValueError(f"expected {width} fields")
                capture, tick, time, sensor, frame, file = row[:6]
                if width == 7:
                    int(row[6])
                key = int(capture)
                entry = by_capture.setdefault(key, (int(tick), float(time), []))
                entry[2].append((sensor, frame, file))
            except ValueError:
                raise input_error(index, f"malformed row {','.join(row)!r}", line) from None
        self.captures = [(k, *by_capture[k]) for k in sorted(by_capture)]
        self.sensors = list(self.kinds)
        self.calibration = {}
        for name in self.sensors:
            file = folder / name / "calibration.json"
            if file.exists():
                self.calibration[name] = _read_json(file)

    def __len__(self):
        return len(self.captures)

    def frame(self, i):
        capture, tick, time, files = self.captures[i]
        by_sensor = {}
        for sensor, _, file in files:
            by_sensor.setdefault(sensor, []).append(self.folder / file)
        data, labels, poses, entities = {}, {}, {}, []
        for sensor, paths in by_sensor.items():
            if sensor == "poses":
                pose = _read_json(paths[0])
                for s in pose.get("sensors", []):
                    poses[s["sensor"]] = np.array(s["world_from_sensor"], dtype=np.float64)
                entities = pose.get("entities", [])
                continue
            for path in paths:
                if path.name.endswith("_labels.json"):
                    labels[sensor] = _read_json(path)
            data[sensor] = self._sensor_data(sensor, paths, time)
        calibration = {s: self.calibration[s] for s in data if s in self.calibration}
        return Frame(tick=tick, time=time, data=data, labels=labels, poses=poses,
                     calibration=calibration, entities=entities, index=capture)

    def _sensor_data(self, sensor, paths, time):
        kind = self.kinds.get(sensor)
        by_suffix = {}
        for path in paths:
            name = path.name
            suffix = name[name.index("_"):] if "_" in name else path.suffix
            by_suffix[suffix] = path
        if kind == "Lidar":
            if ".pcd" in by_suffix:
                return read_pcd(by_suffix[".pcd"], time)
            raise input_error(paths[0], f"LiDAR '{sensor}' has no .pcd file in this capture")
        if kind == "DepthCamera" and ".exr" in by_suffix:
            return _images().read(by_suffix[".exr"])
        if ".png" not in by_suffix:
            raise input_error(paths[0], f"sensor '{sensor}' has no image in this capture")
        image = _images().read(by_suffix[".png"])
        if kind == "DepthCamera":  # 16-bit millimetres, 0 = none
            return image.astype(np.float32) / np.float32(1000.0)
        if kind == "SemanticCamera":
            return image.astype(np.uint16)
        return image


def _kitti_labels(path):
    labels = []
    with open(path, encoding="utf-8") as f:
        for line, text in enumerate(f, start=1):
            parts = text.split()
            if not parts:
                continue
            try:
                v = [float(x) for x in parts[1:15]]
                labels.append({"type": parts[0], "truncated": v[0], "occluded": int(v[1]),
                               "alpha": v[2], "bbox": v[3:7], "dimensions": v[7:10],
                               "location": v[10:13], "rotation_y": v[13]})
            except (ValueError, IndexError):
                raise input_error(path, "not a KITTI label line", line) from None
    return labels


def _kitti_calib(path):
    calib = {}
    with open(path, encoding="utf-8") as f:
        for line, text in enumerate(f, start=1):
            key, _, values = text.partition(":")
            if not values.strip():
                continue
            try:
                numbers = np.array([float(x) for x in values.split()], dtype=np.float64)
            except ValueError:
                raise input_error(path, f"'{key}' is not a list of numbers", line) from None
            calib[key.strip()] = numbers.reshape(3, -1) if numbers.size in (9, 12) else numbers
    return calib


class _KittiLayout:
    """KITTI object detection: image_2/, velodyne/, label_2/, calib/ with NNNNNN stems."""

    def __init__(self, folder):
        self.folder = folder
        stems = set()
        for sub, suffix in (("image_2", ".png"), ("velodyne", ".bin")):
            if (folder / sub).is_dir():
                stems |= {p.stem for p in (folder / sub).glob("*" + suffix)}
        self.stems = sorted(stems)
        self.run = None
        self.sensors = [s for s in ("image_2", "velodyne") if (folder / s).is_dir()]
        self.calibration = {}

    def __len__(self):
        return len(self.stems)

    def frame(self, i):
        stem = self.stems[i]
        f = self.folder
        data, labels, calibration = {}, {}, {}
        if (f / "image_2" / f"{stem}.png").exists():
            data["image_2"] = _images().read(f / "image_2" / f"{stem}.png")
        velodyne = f / "velodyne" / f"{stem}.bin"
        if velodyne.exists():
            raw = np.fromfile(velodyne, dtype="<f4")
            if raw.size % 4:
                raise input_error(velodyne, "not KITTI velodyne points (float32 x y z intensity)")
            data["velodyne"] = raw.reshape(-1, 4)
        if (f / "label_2" / f"{stem}.txt").exists():
            labels["label_2"] = _kitti_labels(f / "label_2" / f"{stem}.txt")
        if (f / "calib" / f"{stem}.txt").exists():
            calibration["calib"] = _kitti_calib(f / "calib" / f"{stem}.txt")
        return Frame(tick=None, time=None, data=data, labels=labels, calibration=calibration,
                     index=int(stem) if stem.isdigit() else i)


class Dataset:
    """The frames of a dataset folder, indexable and iterable.

    Dataset(folder, layout=None)

    A Corsa dataset (`corsa run --rig ... -o DIR`, corsa.collect): one Frame per capture, with
    every sensor captured then (frame.data[sensor] as in Simulation.capture()), its labels,
    sensor poses, calibration and every entity. A KITTI folder (image_2/, velodyne/, label_2/,
    calib/, directly or in training/), or the kitti/ export of a Corsa dataset with layout='kitti': frame.data holds
    'image_2' (uint8 HxWx3) and 'velodyne' (float32 Nx4: x y z intensity), frame.labels
    'label_2' (dicts), frame.calibration 'calib' (P0..P3, R0_rect, Tr_velo_to_cam, ...).
    layout: None (by content), 'corsa' or 'kitti'. Bad or missing files raise corsa.InputError.
    """

    def __init__(self, folder, layout=None):
        folder = Path(os.fspath(folder))
        if layout not in (None, "corsa", "kitti"):
            raise ValueError(f"layout expects 'corsa' or 'kitti', not {layout!r}")
        if not folder.is_dir():
            raise input_error(folder, "no such dataset folder")
        if layout == "kitti" and (folder / "kitti").is_dir():
            folder = folder / "kitti"
        # KITTI's own layout keeps the frames in training/ (beside ImageSets/).
        if layout != "corsa" and not (folder / "frames.csv").exists() \
                and (folder / "training").is_dir() and not (folder / "image_2").is_dir():
            folder = folder / "training"
        if layout is None:
            if (folder / "frames.csv").exists():
                layout = "corsa"
            elif (folder / "image_2").is_dir() or (folder / "velodyne").is_dir():
                layout = "kitti"
            else:
                raise input_error(folder, "neither a Corsa dataset (frames.csv) nor a KITTI "
                                  "folder (image_2/, velodyne/)")
        self.folder = folder
        self.layout = layout
        self._impl = _CorsaLayout(folder) if layout == "corsa" else _KittiLayout(folder)

    def __len__(self):
        return len(self._impl)

    def __getitem__(self, index):
        if isinstance(index, slice):
            return [self[i] for i in range(*index.indices(len(self)))]
        index = int(index)
        if index < 0:
            index += len(self)
        if not 0 <= index < len(self):
            raise IndexError(f"frame {index} of a dataset of {len(self)}")
        return self._impl.frame(index)

    def __iter__(self):
        for i in range(len(self)):
            yield self[i]

    @property
    def sensors(self):
        """Sensor names (Corsa: the rig's; KITTI: 'image_2', 'velodyne')."""
        return list(self._impl.sensors)

    @property
    def calibration(self):
        """{sensor: calibration.json} of a Corsa dataset ({} for KITTI: see frame.calibration)."""
        return dict(self._impl.calibration)

    @property
    def run(self):
        """run.json of a Corsa dataset (scenario, parameters, seed, rig, ...); None for KITTI."""
        return self._impl.run

    def torch(self, transform=None):
        """This dataset as a PyTorch map-style Dataset (corsa.TorchDataset)."""
        from ._torch import TorchDataset

        return TorchDataset(self, transform=transform)

    def __repr__(self):
        return f"<corsa.Dataset {self.folder} ({self.layout}, {len(self)} frames)>"
