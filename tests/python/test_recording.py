"""s2sim.recording reads what `s2sim-run --record` writes (docs/recording.md): the frames at the
log period hold the run's times, poses, twists, signals and snapshots, the same as the CSV log
of the same run and as the bindings stepping the same run; a bad file is a RecordingError that
names it and its fault."""

import csv
import os
import subprocess

import numpy as np
import pytest

import s2sim
from s2sim import recording

SOURCE = os.environ.get("S2SIM_SOURCE_DIR", os.getcwd())
BIN = os.environ.get("S2SIM_BIN_DIR", os.path.join(SOURCE, "build", "bin"))
NXT = os.path.join(SOURCE, "scenes", "nxt")
DRIVE = ["robots/nxt/axes/left/ref_voltage=6", "robots/nxt/axes/right/ref_voltage=-3"]


@pytest.fixture(scope="module")
def recorded(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("recording")
    rec, log = tmp / "nxt.s2rec", tmp / "nxt.csv"
    subprocess.run([os.path.join(BIN, "s2sim-run"), NXT, "--duration", "1", "--log-period",
                    "0.05", "--record", str(rec), "--log", str(log), "--quiet", "--set"] + DRIVE,
                   check=True)
    return rec, log


def test_the_recording_holds_the_logged_run(recorded):
    rec = recording.read(recorded[0])
    assert rec.version == 1 and len(rec) == 21 and rec.period_ticks == 50
    assert rec.scene == os.path.realpath(os.path.join(NXT, "scene.xml"))
    assert rec.time == pytest.approx(np.arange(21) * 0.05, abs=1e-12)
    assert list(rec.tick) == list(range(0, 1001, 50))
    assert rec.position.shape == (21, len(rec.bodies), 3)
    assert rec.quaternion.shape == (21, len(rec.bodies), 4)
    assert rec.values.shape == (21, len(rec.signals))
    assert np.allclose(np.linalg.norm(rec.quaternion, axis=2), 1.0, atol=1e-12)
    with open(recorded[1]) as f:
        rows = list(csv.reader(f))
    header, table = rows[0], np.array(rows[1:], dtype=float)
    assert table.shape[0] == 21
    for column, title in enumerate(header[1:], 1):
        name = title.rsplit(" [", 1)[0]
        # The CSV's %.10g against the recording's binary64.
        assert rec.signal(name) == pytest.approx(table[:, column], rel=1e-9, abs=1e-12), name
    brick = rec.body("robots/nxt/solids/brick")
    assert rec.position[-1, brick, 0] != rec.position[0, brick, 0]  # it drove


def test_the_bindings_stepping_the_same_run_have_the_recorded_poses(recorded):
    rec = recording.read(recorded[0])
    sim = s2sim.Simulation(NXT)
    for assignment in DRIVE:
        name, value = assignment.split("=")
        sim.set_input(name, float(value))
    assert sim.body_names()[1:] == rec.bodies
    for k in range(len(rec)):
        if k:
            sim.step(50)
        for b, name in enumerate(rec.bodies):
            position, rotation = sim.body_pose(name)
            assert np.array_equal(np.asarray(position), rec.position[k, b]), (k, name)
            w, x, y, z = rec.quaternion[k, b]
            from_quaternion = np.array([
                [1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])
            assert np.allclose(np.asarray(rotation), from_quaternion, atol=1e-14)
            linear, angular = sim.body_twist(name)
            assert np.array_equal(np.asarray(linear), rec.linear_velocity[k, b])
            assert np.array_equal(np.asarray(angular), rec.angular_velocity[k, b])
        assert np.array_equal(np.asarray(sim.save().values), rec.state[k]), k


def refusal(path, data):
    path.write_bytes(data)
    with pytest.raises(recording.RecordingError) as e:
        recording.read(path)
    assert str(path) in str(e.value)
    return str(e.value)


def test_bad_files_name_themselves_and_the_fault(recorded, tmp_path):
    good = recorded[0].read_bytes()
    assert "truncated: frame" in refusal(tmp_path / "cut.s2rec", good[:-200])
    assert "end record is missing" in refusal(tmp_path / "open.s2rec", good[:-16])
    assert "not an S2Sim recording" in refusal(tmp_path / "log.csv", recorded[1].read_bytes())
    assert "format version 7" in refusal(tmp_path / "v7.s2rec", good[:8] + b"\x07" + good[9:])
    assert "bytes after the end record" in refusal(tmp_path / "long.s2rec", good + b"\0")
