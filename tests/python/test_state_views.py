"""The state as NumPy views (python/src/state_views.cpp) on scenes/nxt: views that change in
place, their name maps, writing the state (set_state, set_inputs, place_body), reset(seed) and
the errors of bad input."""

import gc
import os
import shutil
import threading
import time

import numpy as np
import pytest

import s2sim

SOURCE = os.environ.get("S2SIM_SOURCE_DIR", os.getcwd())
NXT = os.path.join(SOURCE, "scenes", "nxt")
RIGHT, LEFT = "robots/nxt/axes/right/ref_voltage", "robots/nxt/axes/left/ref_voltage"
RIGHT_AXIS = "robots/nxt/axes/right"


def drive(sim, volts=6.0):
    sim.set_inputs({RIGHT: volts, LEFT: -volts})


def address(array):
    return array.__array_interface__["data"][0]


def test_views_change_in_place_and_agree_with_the_named_reads():
    sim = s2sim.Simulation(NXT)
    q, u, signals = sim.q, sim.u, sim.signal_values
    positions, rotations = sim.body_positions, sim.body_rotations
    linear, angular = sim.body_linear_velocities, sim.body_angular_velocities
    assert q.shape == u.shape == (len(sim.axis_names),) and len(sim.axis_names) >= 2
    assert positions.shape == (len(sim.body_names()), 3)
    assert rotations.shape == (len(sim.body_names()), 3, 3)
    assert signals.shape == (len(sim.list_signals()),)
    before = [a.copy() for a in (q, u, signals, positions, rotations, linear, angular)]
    drive(sim)
    sim.step(300)  # the arrays read before the step now hold the state after it
    for old, new in zip(before, (q, u, signals, positions, rotations, linear, angular)):
        assert not np.array_equal(old, new)
    for i, axis in enumerate(sim.axis_names):
        assert q[i] == sim.signal(axis + "/pos") and u[i] == sim.signal(axis + "/speed")
    ids = sim.signal_ids
    for name in ("time", "robots/nxt/x", "robots/nxt/axes/left/speed", RIGHT):
        assert signals[ids[name]] == sim.signal(name)
    brick = sim.body_ids["robots/nxt/solids/brick"]
    position, rotation = sim.body_pose(brick)
    assert np.array_equal(positions[brick], position)
    assert np.array_equal(rotations[brick], rotation)
    v, w = sim.body_twist(brick)
    assert np.array_equal(linear[brick], v) and np.array_equal(angular[brick], w)
    assert sim.input_values[sim.input_ids[RIGHT]] == 6.0
    assert sim.axis_ids[RIGHT_AXIS] == sim.axis_names.index(RIGHT_AXIS)


def test_views_are_read_only_and_stay_valid_through_reset_restore_and_the_simulation():
    sim = s2sim.Simulation(NXT)
    q, signals, positions = sim.q, sim.signal_values, sim.body_positions
    for view in (q, signals, positions, sim.u, sim.body_rotations, sim.input_values):
        with pytest.raises(ValueError, match="read-only"):
            view[0] = 1.0
    drive(sim)
    sim.step(100)
    snap = sim.save()
    sim.step(100)
    sim.restore(snap)
    assert address(sim.q) == address(q) and address(sim.signal_values) == address(signals)
    assert signals[sim.signal_ids["time"]] == pytest.approx(0.1)
    sim.reset()
    assert signals[sim.signal_ids["time"]] == 0.0 and address(sim.body_positions) == \
        address(positions)
    kept = s2sim.Simulation(NXT).body_positions  # the view holds its Simulation alive
    gc.collect()
    assert np.isfinite(kept).all() and kept[1, 2] > 0


def test_set_inputs_by_dict_and_by_array():
    sim = s2sim.Simulation(NXT)
    sim.set_inputs({RIGHT: 3.0, LEFT: -2.0})
    assert sim.input(RIGHT) == 3.0 and sim.input(LEFT) == -2.0
    values = np.array(sim.input_values)
    values[sim.input_ids[RIGHT]] = 5.0
    sim.set_inputs(values)
    assert sim.input(RIGHT) == 5.0 and sim.input(LEFT) == -2.0
    sim.set_inputs(values.astype(np.float32))  # any real dtype
    sim.set_inputs(list(values))


@pytest.mark.parametrize("bad, culprit", [
    ({"robots/nxt/axes/rigth/ref_voltage": 1.0}, "rigth"),     # unknown name, did you mean
    ({RIGHT: "6"}, RIGHT),                                       # not a number
    ({RIGHT: float("nan")}, RIGHT),                              # not finite
    ({3: 1.0}, "3"),                                             # not a name
    (np.zeros(1), "shape"),                                      # wrong shape
    (np.zeros((2, 2)), "shape (2, 2)"),
    (np.array(["a"] * 2), "dtype"),                              # wrong dtype
    (np.zeros(2, dtype=complex), "complex"),
    (np.zeros(2, dtype=bool), "bool"),
])
def test_set_inputs_refuses_bad_input_naming_it_and_changes_nothing(bad, culprit):
    sim = s2sim.Simulation(NXT)
    if isinstance(bad, np.ndarray) and bad.shape == (2,) and len(sim.list_inputs()) != 2:
        bad = np.resize(bad, len(sim.list_inputs()))
    sim.set_input(LEFT, 1.5)
    before = np.array(sim.input_values)
    with pytest.raises(s2sim.UsageError, match=None) as error:
        sim.set_inputs({LEFT: 7.0, **bad} if isinstance(bad, dict) else bad)
    assert culprit in str(error.value)
    assert np.array_equal(sim.input_values, before)  # the good value before it was not set


def test_set_state_writes_axes_and_the_bodies_follow():
    sim = s2sim.Simulation(NXT, defines={"lift": 1})  # in the air: the wheels turn freely
    sim.step(50)
    wheel = sim.body_ids["robots/nxt/solids/Tyre -90"]  # the right wheel (axis angle -90)
    a = sim.axis_ids[RIGHT_AXIS]
    rotation_before = sim.body_rotations[wheel].copy()
    q = np.array(sim.q)
    q[a] += 1.0
    sim.set_state(q=q)
    assert sim.q[a] == q[a] and sim.signal(RIGHT_AXIS + "/pos") == q[a]
    assert not np.allclose(sim.body_rotations[wheel], rotation_before, atol=0.1)  # 1 rad more
    sim.set_state(u={RIGHT_AXIS: 2.5})
    assert sim.u[a] == 2.5 and sim.q[a] == q[a]
    assert sim.signal_values[sim.signal_ids[RIGHT_AXIS + "/speed"]] == 2.5
    sim.step(10)  # and it steps on from there, turning on (the shorted motor brakes it)
    assert q[a] < sim.q[a] < q[a] + 2.5 * 0.01


def test_set_state_repeats_bit_for_bit():
    def run():
        sim = s2sim.Simulation(NXT, seed=3)
        sim.step(100)
        sim.set_state(q={RIGHT_AXIS: 0.5}, u={RIGHT_AXIS: 1.0})
        drive(sim)
        sim.step(300)
        return np.array(sim.signal_values)

    assert np.array_equal(run(), run())


@pytest.mark.parametrize("kwargs, culprit", [
    ({"q": {"robots/nxt/axes/rihgt": 1.0}}, "rihgt"),
    ({"q": {RIGHT_AXIS: float("inf")}}, RIGHT_AXIS),
    ({"u": np.zeros(7)}, "shape (7,)"),
    ({"q": np.array(["x", "y"])}, "dtype"),
    ({"q": {99: 1.0}}, "99"),
    ({"q": "fast"}, "dtype"),
])
def test_set_state_refuses_bad_input_naming_it(kwargs, culprit):
    sim = s2sim.Simulation(NXT)
    sim.step(10)
    before = sim.save()
    with pytest.raises(s2sim.UsageError) as error:
        sim.set_state(**kwargs)
    assert culprit in str(error.value)
    assert sim.save() == before


def test_place_body_moves_a_free_body_at_rest_and_refuses_others():
    sim = s2sim.Simulation(NXT)
    drive(sim)
    sim.step(300)
    row = sim.body_ids["robots/nxt/solids/brick"]
    turn = np.array([[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]])
    sim.place_body("robots/nxt", [1.0, 2.0, 0.2], turn)
    assert np.allclose(sim.body_positions[row, :2], [1.0, 2.0], atol=0.05)
    assert np.allclose(sim.body_rotations[row], turn, atol=1e-9)
    assert np.allclose(sim.body_linear_velocities[row], 0) and sim.signal("robots/nxt/vx") == 0
    sim.place_body("robots/nxt", np.array([0.0, 0.0, 0.3]))  # keeps the rotation
    assert np.allclose(sim.body_rotations[row], turn, atol=1e-9)
    with pytest.raises(s2sim.UsageError, match="rotation matrix"):
        sim.place_body("robots/nxt", [0, 0, 0.2], 2 * np.eye(3))
    with pytest.raises(s2sim.UsageError, match="position"):
        sim.place_body("robots/nxt", [0, 0])
    with pytest.raises(s2sim.UsageError, match="robots/nxt/solids/nope"):
        sim.place_body("robots/nxt/solids/nope", [0, 0, 0.2])
    jointed = "robots/nxt/solids/Tyre 90"  # the left wheel, on its axle
    with pytest.raises(s2sim.UsageError, match="cannot be placed"):
        sim.place_body(jointed, [0, 0, 0.2])


def noisy_nxt(tmp_path):
    """scenes/nxt with its encoders' noise on (stdev 2 ticks a sample)."""
    scene = tmp_path / "nxt"
    shutil.copytree(NXT, scene)
    robot = scene / "nxt.xml"
    text = robot.read_text()
    assert "stdev='-1'" in text
    robot.write_text(text.replace("stdev='-1'", "stdev='2'"))
    return str(scene)


def test_reset_with_a_seed_gives_new_noise_per_seed_and_the_same_for_the_same_seed(tmp_path):
    sim = s2sim.Simulation(noisy_nxt(tmp_path), seed=1)
    encoders = sim.signal_names("robots/nxt/axes/*/encoder")
    assert encoders

    def episode(seed):
        sim.reset(seed=seed)
        assert sim.seed == seed
        drive(sim)
        sim.run_until(0.5)
        return sim.signals(encoders)

    five, six, five_again = episode(5), episode(6), episode(5)
    assert np.array_equal(five, five_again)
    assert not np.array_equal(five, six)
    sim.reset()  # a plain reset keeps the last seed
    assert sim.seed == 5


def test_new_entry_points_are_refused_while_another_thread_steps():
    sim = s2sim.Simulation(NXT)
    drive(sim)
    refused, stepping, done = [], threading.Event(), threading.Event()

    def long_step():
        stepping.set()
        sim.step(60000)
        done.set()

    thread = threading.Thread(target=long_step)
    thread.start()
    stepping.wait()
    calls = (lambda: sim.set_inputs({RIGHT: 1.0}), lambda: sim.set_state(u={RIGHT_AXIS: 0}),
             lambda: sim.q, lambda: sim.signal_values, lambda: sim.contacts(),
             lambda: sim.cast_ray([0, 0, 1], [0, 0, -1], 2.0),
             lambda: sim.place_body("robots/nxt", [0, 0, 0.2]), lambda: sim.reset(seed=2))
    tried = set()
    while not done.is_set() and len(tried) < len(calls):
        for i, call in enumerate(calls):
            try:
                call()
            except s2sim.UsageError as e:
                assert "in use by another thread" in str(e), str(e)
                refused.append(i)
                tried.add(i)
        time.sleep(0.001)
    thread.join()
    assert refused, "the long step ended before a second call could be tried"


def test_set_state_refuses_a_loop_closing_axis_and_changes_nothing():
    sim = s2sim.Simulation(os.path.join(SOURCE, "scenes", "default"))  # it has loops
    sim.step(10)
    before = sim.save()
    with pytest.raises(s2sim.UsageError, match="closes a kinematic loop") as error:
        sim.set_state(q=np.array(sim.q) + 0.1)  # every axis moved, loop axes among them
    assert any(name in str(error.value) for name in sim.axis_names)
    assert sim.save() == before


def test_things_added_and_deleted_while_running():
    sim = s2sim.Simulation(NXT, runtime_things=2)
    spare = [t for t in sim.things if t["added"]]
    assert len(spare) == 2 and not any(t["present"] for t in spare)
    sim.run_until(0.2)
    body = sim.add_thing("sphere", [0.05], mass=0.3, position=[1.0, 1.0, 1.0], color=[1, 0, 0],
                         id="ball")
    assert body == spare[0]["body"]
    assert sim.body_names()[body] == "runtime_things/0"
    assert [t["id"] for t in sim.things if t["present"] and t["added"]] == ["ball"]
    sim.run_until(0.5)
    # Free fall from rest for 0.3 s.
    assert abs(sim.signal("runtime_things/0/z") - (1.0 - 0.5 * 9.81 * 0.3 ** 2)) < 2e-3
    snap = sim.save()
    sim.run_until(1.5)
    assert abs(sim.signal("runtime_things/0/z") - 0.05) < 2e-3  # on the floor
    landed = sim.signal_values.copy()
    sim.delete_thing(body)
    assert not sim.things[-2]["present"]
    sim.restore(snap)
    assert sim.things[-2]["present"] and sim.things[-2]["id"] == "ball"
    sim.run_until(1.5)
    assert np.array_equal(sim.signal_values, landed)
    sim.reset()
    assert not any(t["present"] for t in sim.things if t["added"])
    with pytest.raises(s2sim.Error, match="shape must be 'box', 'sphere' or 'cylinder'"):
        sim.add_thing("cone", [0.1])
    with pytest.raises(s2sim.Error, match="mass must be positive"):
        sim.add_thing("box", [0.1, 0.1, 0.1], mass=-1)
    sim.add_thing("box", [0.1, 0.1, 0.1])
    sim.add_thing("cylinder", [0.05, 0.2])
    with pytest.raises(s2sim.Error, match="all 2 spare bodies hold things"):
        sim.add_thing("box", [0.1, 0.1, 0.1])
    with pytest.raises(s2sim.Error, match="is not a thing"):
        sim.delete_thing("robots/nxt")


def test_a_fixed_thing_is_an_obstacle_and_scene_obstacles_can_be_deleted():
    sim = s2sim.Simulation(NXT, runtime_things=2)
    shelf = sim.add_thing("box", [0.4, 0.4, 0.02], position=[2.0, 2.0, 0.5], fixed=True, id="shelf")
    sim.add_thing("box", [0.1, 0.1, 0.1], mass=0.5, position=[2.0, 2.0, 0.8], id="parcel")
    sim.run_until(1.0)
    assert sim.signal("runtime_things/0/z") == 0.5
    assert abs(sim.signal("runtime_things/1/z") - 0.56) < 2e-3
    sim.delete_thing(shelf)
    sim.run_until(2.0)
    assert abs(sim.signal("runtime_things/1/z") - 0.05) < 2e-3
    with pytest.raises(s2sim.Error, match="no obstacle 0"):
        sim.delete_obstacle(0)  # nxt has none


def test_a_body_resized_and_its_surface_set_while_running():
    sim = s2sim.Simulation(NXT, runtime_things=1)
    box = sim.add_thing("box", [0.1, 0.1, 0.1], position=[2.0, 2.0, 0.05])
    sim.run_until(0.5)
    sim.resize_body(box, [0.1, 0.1, 0.3])
    sim.set_body_surface(box, 0.5)
    sim.run_until(1.5)
    assert abs(sim.signal("runtime_things/0/z") - 0.15) < 2e-3
    with pytest.raises(s2sim.Error, match="sizes must be positive"):
        sim.resize_body(box, [0.1, 0.0, 0.1])
    with pytest.raises(s2sim.Error, match="must be finite"):
        sim.set_body_surface(box, float("nan"))


PENDULUM = os.path.join(SOURCE, "tests", "kernel", "sim", "fixtures", "pendulum_mass")
BOB = "robots/pendulum/solids/bob"


def swing_period(sim, swings=2):
    """Mean period from the times the hinge's rate crosses zero upwards."""
    crossings, last, last_t = [], sim.u[0], sim.time
    while len(crossings) < swings + 1 and sim.time < 20:
        sim.step()
        now, t = sim.u[0], sim.time
        if last < 0 <= now:
            crossings.append(last_t + (t - last_t) * (-last) / (now - last))
        last, last_t = now, t
    return (crossings[-1] - crossings[0]) / (len(crossings) - 1)


def test_a_body_mass_set_while_running_moves_its_pendulum_as_its_length_says():
    sim = s2sim.Simulation(PENDULUM)
    loaded = sim.body_mass(BOB)
    assert loaded["mass"] == 1.0 and np.all(loaded["com"] == 0)
    before = swing_period(sim)
    sim.set_body_mass(BOB, 2.0)  # SimTwo's rule: the inertia doubles too
    assert np.allclose(sim.body_mass(BOB)["inertia"], 2 * loaded["inertia"])
    assert abs(swing_period(sim) - before) < 1e-4 * before
    # The centre of mass halfway up to the hinge: a quarter of the length, √½ of the period.
    up = 0.25 * np.array([-np.sin(0.1), 0.0, np.cos(0.1)])
    sim.set_body_mass(BOB, 2.0, com=up)
    assert abs(swing_period(sim, 3) / before - np.sqrt(0.5)) < 4e-3
    with pytest.raises(s2sim.Error, match="A \\+ B >= C"):
        sim.set_body_mass(BOB, 1.0, inertia=np.diag([1.0, 1.0, 3.0]))
    sim.reset()
    assert sim.body_mass(BOB)["mass"] == 1.0
