"""Sensors in the loop (Simulation.capture) and datasets (corsa.collect, corsa.Dataset) as numpy
arrays."""

import json

import numpy as np
import pytest

import corsa
from conftest import CUT_IN, ROOT, SMALL_RIG


@pytest.fixture(scope="module")
def captured():
    """The cut-in with the small rig, 0.2 s in (a capture tick of every sensor of the dataset
    fixture), and one capture of every sensor."""
    sim = corsa.Simulation(CUT_IN, rig=SMALL_RIG)
    for _ in range(20):
        sim.step()
    return sim, sim.capture()


def test_capture_gives_every_sensor_as_an_array_of_its_kind(captured):
    sim, frame = captured
    assert [s[0] for s in sim.sensors] == ["cam", "depth", "semantic", "instance", "roof_lidar",
                                          "top"]
    assert set(frame) == {name for name, *_ in sim.sensors}
    assert frame["cam"].shape == (108, 192, 3) and frame["cam"].dtype == np.uint8
    assert frame["depth"].shape == (108, 192) and frame["depth"].dtype == np.float32
    assert frame["semantic"].dtype == np.uint16 and frame["instance"].dtype == np.uint16
    assert frame.tick == sim.tick and frame.time == pytest.approx(sim.time)
    # The road is below the horizon: depth there is finite and within the camera's range.
    road = frame["depth"][-10:, 90:100]
    assert np.all((road > 0) & (road <= 150))
    assert frame["cam"].std() > 5  # a picture, not a flat fill


def test_the_lidar_is_a_structured_array_of_returns_around_the_ego(captured):
    _, frame = captured
    points = frame["roof_lidar"]
    assert points.dtype.names == ("x", "y", "z", "intensity", "ring", "class", "instance", "time")
    assert len(points) > 1000
    distance = np.hypot(points["x"], points["y"])
    assert distance.max() <= 80.5 and set(np.unique(points["ring"])) <= set(range(16))


def test_the_cutter_is_labelled_and_posed(captured):
    sim, frame = captured
    names = {entity["name"] for entity in frame.entities}
    assert names == {"Ego", "Cutter"}
    ego = next(e for e in frame.entities if e["name"] == "Ego")
    assert ego["pose"][0] == pytest.approx(sim.state("Ego").x, abs=1e-6)
    pose = frame.poses["cam"]
    assert pose.shape == (4, 4) and np.allclose(pose[3], [0, 0, 0, 1])
    # The camera sits 1.6 m ahead of the ego's reference point, 1.45 m up (small_rig.xml).
    assert pose[2, 3] == pytest.approx(sim.state("Ego").z + 1.45, abs=0.05)
    assert "objects" in frame.labels["cam"]


def test_capture_renders_only_the_sensors_named(captured):
    sim, _ = captured
    frame = sim.capture("depth")
    assert list(frame) == ["depth"]
    with pytest.raises(ValueError):
        sim.capture(["nope"])


def test_capture_without_a_rig_is_refused():
    with pytest.raises(ValueError, match="no rig"):
        corsa.Simulation(CUT_IN).capture()


def test_a_dataset_reads_back_what_collect_wrote(dataset):
    data = corsa.Dataset(dataset)
    run = json.loads((dataset / "run.json").read_text())
    assert data.layout == "corsa" and data.run == run
    assert data.sensors == [s["name"] for s in run["sensors"]]
    frames = list(data)
    assert len(frames) == len(data) > 1
    assert [f.index for f in frames] == sorted(f.index for f in frames)
    first = data[0]
    assert first["cam"].shape == (108, 192, 3) and first["cam"].dtype == np.uint8
    assert first["depth"].dtype == np.float32 and first["semantic"].dtype == np.uint16
    assert first["roof_lidar"].dtype.names[:3] == ("x", "y", "z")
    assert first.poses["cam"].shape == (4, 4)
    assert data[-1].index == frames[-1].index
    assert [f.index for f in data[:2]] == [frames[0].index, frames[1].index]
    with pytest.raises(IndexError):
        data[len(data)]


def test_a_dataset_frame_matches_a_capture_at_the_same_tick(dataset, captured):
    sim, frame = captured
    stored = next(f for f in corsa.Dataset(dataset) if f.tick == sim.tick)
    # Semantic classes are exact; depth went through the dataset's files.
    assert np.array_equal(frame["semantic"], stored["semantic"])
    assert np.allclose(frame["depth"], stored["depth"], atol=1e-3)
    # RGB differs by its zero-mean sensor noise only, which is drawn per capture of the camera.
    live, saved = frame["cam"].astype(float), stored["cam"].astype(float)
    assert live.mean() == pytest.approx(saved.mean(), abs=0.5)
    assert np.corrcoef(live.ravel(), saved.ravel())[0, 1] > 0.9


def test_the_kitti_export_reads_as_kitti(dataset):
    kitti = corsa.Dataset(dataset, layout="kitti")
    assert kitti.layout == "kitti" and len(kitti) > 0
    frame = kitti[0]
    assert frame["image_2"].ndim == 3 and frame["velodyne"].shape[1] == 4
    assert {"P2", "Tr_velo_to_cam"} <= set(frame.calibration["calib"])
    assert all("type" in label for label in frame.labels.get("label_2", []))


def test_the_torch_adapter_gives_dicts_of_arrays(dataset):
    samples = corsa.TorchDataset(dataset, sensors=["cam"])
    assert len(samples) == len(corsa.Dataset(dataset))
    sample = samples[0]
    assert set(sample) == {"cam", "index", "time"} and sample["cam"].shape == (108, 192, 3)


def test_a_folder_that_is_no_dataset_is_an_input_error(tmp_path):
    with pytest.raises(corsa.InputError, match="neither a Corsa dataset"):
        corsa.Dataset(tmp_path)
    (tmp_path / "frames.csv").write_text("nope\n")
    (tmp_path / "run.json").write_text("{}")
    with pytest.raises(corsa.InputError) as caught:
        corsa.Dataset(tmp_path)
    assert caught.value.line == 1 and caught.value.file.endswith("frames.csv")


def _write_cube(path, size=1.0):
    """A cube OBJ `size` metres on a side (an entity model: scaled to the entity's box)."""
    h = size / 2
    corners = [(x, y, z) for x in (-h, h) for y in (-h, h) for z in (0.0, size)]
    faces = [(1, 2, 4, 3), (5, 7, 8, 6), (1, 5, 6, 2), (3, 4, 8, 7), (1, 3, 7, 5), (2, 6, 8, 4)]
    lines = [f"v {x} {y} {z}" for x, y, z in corners] + [f"f {a} {b} {c} {d}" for a, b, c, d in faces]
    path.write_text("\n".join(lines) + "\n")
    return path


def test_entity_models_replace_the_cutters_generated_shape(tmp_path):
    # 8 s in, the cutter fills about 1,500 pixels of the small rig's camera: a generated car,
    # then a box (the model scaled to the cutter's bounding box).
    cube = _write_cube(tmp_path / "box_car.obj")
    frames = []
    for entity_models in ((), [f"Cutter={cube}"]):
        sim = corsa.Simulation(CUT_IN, rig=SMALL_RIG, entity_models=entity_models)
        for _ in range(800):
            sim.step()
        frames.append(sim.capture(["depth", "semantic"]))
    car = 14  # the semantic class id of cars (docs/sensors.md)
    cutter = frames[0].data["semantic"] == car
    assert cutter.sum() > 500
    assert (frames[1].data["semantic"] == car).sum() > 500
    # Only the cutter's shape changed: depth differs where it is, nowhere else.
    differ = np.abs(frames[0].data["depth"] - frames[1].data["depth"]) > 0.05
    assert differ.sum() > 20
    assert not (differ & ~cutter & (frames[1].data["semantic"] != car)).any()


def test_entity_models_are_checked_as_on_the_command_line(tmp_path):
    with pytest.raises(ValueError, match="expected WHO=FILE"):
        corsa.Simulation(CUT_IN, rig=SMALL_RIG, entity_models=["car.glb"])
    with pytest.raises(corsa.InputError, match="neither an entity of the scenario nor a category"):
        corsa.Simulation(CUT_IN, rig=SMALL_RIG, entity_models=["Cuter=car.glb"])
    with pytest.raises(ValueError, match="for a rig"):
        corsa.Simulation(CUT_IN, entity_models=["car=car.glb"])
    missing = tmp_path / "nothere.glb"
    sim = corsa.Simulation(CUT_IN, rig=SMALL_RIG, entity_models=[f"car={missing}"])
    # The model is loaded for the first capture that shows a car: a warning, the generated
    # shape stands in.
    with pytest.warns(corsa.CorsaWarning, match="nothere.glb"):
        frame = sim.capture("depth")
    assert frame.data["depth"].shape == (108, 192)


def test_collect_takes_entity_models(tmp_path):
    cube = _write_cube(tmp_path / "box_car.obj")
    folder = tmp_path / "data"
    report = corsa.collect(CUT_IN, SMALL_RIG, folder, duration=0.2,
                           entity_models=[f"car={cube}"])
    assert report["captures"] > 0
    with pytest.raises(corsa.InputError, match="neither an entity"):
        corsa.collect(CUT_IN, SMALL_RIG, tmp_path / "other", duration=0.2,
                      entity_models=["Cuter=car.glb"])


LIGHTS = ROOT / "tests/collect/fixtures/braking_lights.xosc"
LIGHTS_RIG = ROOT / "tests/collect/fixtures/lights_rig.xml"


def test_vehicle_lights_are_in_the_labels_of_a_dataset_and_of_a_capture(tmp_path):
    """Lead brakes from 0.5 s and flashes its left indicator green (0.4 s on, 0.4 s off)."""
    folder = tmp_path / "lights"
    corsa.collect(LIGHTS, LIGHTS_RIG, folder)
    at = {round(frame.time, 2): frame for frame in corsa.Dataset(folder)}

    def lead(labels):
        return next(o for o in labels["cam"]["objects"] if o["name"] == "Lead")

    before = lead(at[0.4].labels)
    assert before["lights"] == {} and before["lamps"] == []
    lit = lead(at[0.8].labels)
    assert lit["lights"]["brakeLights"] == {"mode": "on", "lit": True}
    assert lit["lights"]["indicatorLeft"] == {"mode": "flashing", "lit": True, "set": True,
                                              "intensity_cd": 200, "colour": [0, 1, 0]}
    assert lit["lamps"] == ["brake", "indicator_left"]
    off_phase = lead(at[1.2].labels)
    assert off_phase["lights"]["indicatorLeft"]["lit"] is False
    assert off_phase["lamps"] == ["brake"]
    # Simulation.capture() labels the same lights at the same tick.
    sim = corsa.Simulation(LIGHTS, rig=LIGHTS_RIG)
    for _ in range(80):
        sim.step()
    live = lead(sim.capture("cam").labels)
    assert live["lights"] == lit["lights"] and live["lamps"] == lit["lamps"]
