"""Contacts and ray casts from Python (python/src/queries.cpp), and snapshots that pickle and
save to disk (python/src/snapshots.cpp, s2sim/snapshots.py) and restore bit for bit."""

import os
import pickle

import numpy as np
import pytest

import s2sim

SOURCE = os.environ.get("S2SIM_SOURCE_DIR", os.getcwd())
NXT = os.path.join(SOURCE, "scenes", "nxt")
RIGHT, LEFT = "robots/nxt/axes/right/ref_voltage", "robots/nxt/axes/left/ref_voltage"


def drive(sim, volts=6.0):
    sim.set_inputs({RIGHT: volts, LEFT: -volts})


def total_mass_kg(sim):
    """The robot's weight as contact carries it at rest: the sum of the normal forces / g."""
    c = sim.contacts()
    return c["force"][:, 2].sum() / 9.81


def test_contacts_of_the_robot_at_rest_carry_its_weight_on_the_ground():
    sim = s2sim.Simulation(NXT)
    sim.run_until(1.0)  # settled
    c = sim.contacts()
    n = sim.contact_count
    assert n >= 3 and n == int(sim.signal("contacts/count"))
    assert c["point"].shape == c["normal"].shape == c["force"].shape == (n, 3)
    assert c["body_a"].shape == c["body_b"].shape == c["depth"].shape == (n,)
    assert (c["body_b"] == 0).all()  # on the ground
    names = sim.body_names()
    assert all(names[b].startswith("robots/nxt/") for b in c["body_a"])
    assert np.allclose(c["normal"], [0, 0, 1], atol=1e-9)
    assert np.allclose(c["point"][:, 2], 0, atol=2e-3)
    # The NXT's masses: brick 0.31, motors 2 x 0.08, the caster and wheels; at rest the
    # ground carries all of it (the contact_force signals agree point by point).
    weight = c["force"][:, 2].sum()
    assert weight > 0
    per_body = {}
    for b, f in zip(c["body_a"], c["force"]):
        per_body[b] = per_body.get(b, 0) + f
    for b, f in per_body.items():
        assert np.linalg.norm(f) == pytest.approx(sim.signal(names[b] + "/contact_force"),
                                                  rel=1e-9)
    sim.run_until(1.2)
    assert total_mass_kg(sim) == pytest.approx(weight / 9.81, rel=1e-3)  # steady


def test_rays_hit_the_robot_the_ground_or_nothing():
    sim = s2sim.Simulation(NXT)
    sim.step(100)
    brick = sim.body_ids["robots/nxt/solids/brick"]
    top = sim.body_positions[brick] + [0, 0, 1.0]
    hit = sim.cast_ray(top, [0, 0, -1], 2.0)
    assert hit["body"] == brick and hit["body_name"] == "robots/nxt/solids/brick"
    # The brick's top face, 20 mm above its centre (the robot leans a little on its caster).
    assert hit["point"][2] == pytest.approx(sim.body_positions[brick][2] + 0.02, abs=2e-3)
    assert np.allclose(hit["normal"], [0, 0, 1], atol=2e-2)
    assert hit["distance"] == pytest.approx(top[2] - hit["point"][2])
    skipped = sim.cast_ray(top, [0, 0, -1], 2.0, ignore_body="robots/nxt/solids/brick")
    assert skipped is None or skipped["body"] != brick
    ground = sim.cast_ray([3.0, 3.0, 1.0], [0, 0, -5.0], 2.0)  # the direction need not be unit
    assert ground["body"] == 0 and ground["distance"] == pytest.approx(1.0)
    assert sim.cast_ray([3.0, 3.0, 1.0], [0, 0, 1], 2.0) is None  # up: nothing
    fan = sim.cast_rays([3.0, 3.0, 1.0], [[0, 0, -1], [0, 0, 1], [1, 0, -1]], 5.0)
    assert fan["hit"].tolist() == [True, False, True]
    assert fan["point"].shape == (3, 3) and np.isnan(fan["point"][1]).all()
    assert fan["distance"][1] == np.inf and fan["body"][1] == -1
    assert fan["distance"][2] == pytest.approx(np.sqrt(2.0))


@pytest.mark.parametrize("args, culprit", [
    (([0, 0, 1], [0, 0, 0], 1.0), "zero vector"),
    (([0, 0, 1], [0, 0, -1], -1.0), "max_distance"),
    (([0, 0, 1], [0, 0, -1], float("inf")), "max_distance"),
    (([0, 1], [0, 0, -1], 1.0), "origins"),
    (([0, 0, 1], [[0, 0, -1]] * 2, 1.0), None),  # fine: one origin, two directions
    (([[0, 0, 1]] * 3, [[0, 0, -1]] * 2, 1.0), "as many rows"),
    (([0, 0, float("nan")], [0, 0, -1], 1.0), "not finite"),
    ((["a", "b", "c"], [0, 0, -1], 1.0), "dtype"),
])
def test_bad_rays_are_refused_naming_the_argument(args, culprit):
    sim = s2sim.Simulation(NXT)
    if culprit is None:
        assert sim.cast_rays(*args)["hit"].shape == (2,)
        return
    with pytest.raises(s2sim.UsageError) as error:
        sim.cast_rays(*args)
    assert culprit in str(error.value)


def run_on(sim, ticks=400):
    drive(sim, 5.0)
    sim.step(ticks)
    return np.array(sim.signal_values), sim.save()


def test_a_snapshot_pickles_and_restores_into_a_new_simulation_bit_for_bit():
    sim = s2sim.Simulation(NXT, seed=4)
    drive(sim)
    sim.run_until(0.4)
    snap = sim.save()
    copy = pickle.loads(pickle.dumps(snap))
    assert copy == snap and copy.time == snap.time and copy.layout == snap.layout
    assert copy.segments == snap.segments and np.array_equal(copy.values, snap.values)
    expected, expected_end = run_on(sim)
    other = s2sim.Simulation(NXT, seed=4)
    other.restore(copy)
    got, got_end = run_on(other)
    assert np.array_equal(got, expected) and got_end == expected_end


def test_a_snapshot_saves_to_a_file_and_loads_back_bit_for_bit(tmp_path):
    sim = s2sim.Simulation(NXT, seed=2)
    drive(sim)
    sim.run_until(0.3)
    snap = sim.save()
    path = tmp_path / "at-0.3.snapshot"
    snap.save(path)
    assert path.exists() and not (tmp_path / "at-0.3.snapshot.npz").exists()
    loaded = s2sim.Snapshot.load(path)
    assert loaded == snap
    assert s2sim.load_snapshot(str(path)) == snap
    expected, _ = run_on(sim)
    other = s2sim.Simulation(NXT, seed=2)
    other.restore(loaded)
    assert np.array_equal(run_on(other)[0], expected)


def test_bad_snapshot_files_and_pickles_are_refused(tmp_path):
    junk = tmp_path / "junk"
    junk.write_bytes(b"not a snapshot")
    with pytest.raises(s2sim.UsageError, match="not a snapshot file"):
        s2sim.Snapshot.load(junk)
    np.savez(open(tmp_path / "partial", "wb"), values=np.zeros(3))
    with pytest.raises(s2sim.UsageError, match="no format"):
        s2sim.Snapshot.load(tmp_path / "partial")
    sim = s2sim.Simulation(NXT)
    _, state, segments, values, t = sim.save().__getstate__()
    with pytest.raises(s2sim.UsageError, match="version"):
        s2sim.Snapshot.__new__(s2sim.Snapshot).__setstate__((99, state, segments, values, t))
    cut = s2sim.Snapshot._from_parts(state, segments, values[:-8], t)
    with pytest.raises(s2sim.UsageError):
        sim.restore(cut)  # the kernel checks it before changing anything
    with pytest.raises(s2sim.UsageError, match="whole number"):
        s2sim.Snapshot._from_parts(state, segments, values[:-3], t)
