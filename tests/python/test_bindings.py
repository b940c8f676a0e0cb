"""The s2sim Python bindings (python/src/module.cpp) on scenes/nxt and scenes/cartpole."""

import os
import threading
import time

import numpy as np
import pytest

import s2sim

SOURCE = os.environ.get("S2SIM_SOURCE_DIR", os.getcwd())
NXT = os.path.join(SOURCE, "scenes", "nxt")
CARTPOLE = os.path.join(SOURCE, "scenes", "cartpole")
RIGHT, LEFT = "robots/nxt/axes/right/ref_voltage", "robots/nxt/axes/left/ref_voltage"


def drive(sim, volts=6.0):
    sim.set_input(RIGHT, volts)
    sim.set_input(LEFT, -volts)


def test_load_step_and_time():
    sim = s2sim.Simulation(NXT, seed=1)
    assert sim.time == 0.0 and sim.tick == 0
    assert sim.tick_s == pytest.approx(1e-3)
    sim.step(250)
    assert sim.tick == 250 and sim.time == pytest.approx(0.25)
    sim.run_until(1.0)
    assert sim.time == pytest.approx(1.0)
    sim.step()  # n defaults to one tick
    assert sim.tick == 1001


def test_inputs_drive_the_robot_and_signals_read_it():
    sim = s2sim.Simulation(NXT)
    assert RIGHT in sim.list_inputs() and "robots/nxt/x" in sim.list_signals()
    drive(sim)
    assert sim.input(RIGHT) == 6.0
    sim.run_until(1.0)
    x = sim.signal("robots/nxt/x")
    assert x > 0.1  # it drove forward
    values = sim.signals("robots/nxt/axes/*/speed")
    assert isinstance(values, np.ndarray) and values.dtype == np.float64
    assert sim.signal_names("robots/nxt/axes/*/speed") == [
        "robots/nxt/axes/right/speed", "robots/nxt/axes/left/speed"] or len(values) == 2
    assert values.shape == (len(sim.signal_names("robots/nxt/axes/*/speed")),)
    assert sim.unit("robots/nxt/x") == "m"
    listed = sim.signals(["robots/nxt/y", "robots/nxt/axes/*/speed", "time"])  # in list order
    assert listed[0] == sim.signal("robots/nxt/y") and listed[-1] == sim.time
    assert list(listed[1:-1]) == list(values)


def test_body_poses():
    sim = s2sim.Simulation(NXT)
    names = sim.body_names()
    assert names[0] == "world" and any(n.startswith("robots/nxt/solids/") for n in names)
    drive(sim)
    sim.run_until(0.5)
    position, rotation = sim.body_pose("robots/nxt")
    assert position.shape == (3,) and rotation.shape == (3, 3)
    assert position[0] == pytest.approx(sim.signal("robots/nxt/x"))
    assert np.allclose(rotation @ rotation.T, np.eye(3), atol=1e-9)
    linear, angular = sim.body_twist("robots/nxt")
    assert linear[0] == pytest.approx(sim.signal("robots/nxt/vx"))
    p1, _ = sim.body_pose(names.index(names[1]))  # by index too
    assert p1.shape == (3,)


def test_save_restore_and_reset_repeat_the_run():
    sim = s2sim.Simulation(NXT, seed=7)
    drive(sim)
    sim.run_until(0.3)
    snap = sim.save()
    assert snap.time == pytest.approx(0.3) and snap.values.size > 0
    sim.step(500)
    after = sim.signals("robots/nxt/*")
    sim.restore(snap)
    assert sim.time == pytest.approx(0.3)
    sim.step(500)
    assert np.array_equal(after, sim.signals("robots/nxt/*"))

    sim.reset()
    assert sim.time == 0.0
    drive(sim)  # reset puts inputs back to their initial values
    sim.run_until(0.8)
    first = sim.signals("*")
    again = s2sim.Simulation(NXT, seed=7)
    drive(again)
    again.run_until(0.8)
    assert np.array_equal(first, again.signals("*"))


def test_options_seed_physics_step_defines():
    lifted = s2sim.Simulation(NXT, defines={"lift": 1.0})
    assert lifted.signal("robots/nxt/z") > 0.9
    fine = s2sim.Simulation(NXT, physics_step=5e-4)
    assert fine.tick_s == pytest.approx(5e-4)
    tilted = s2sim.Simulation(CARTPOLE, defines={"tilt_deg": 10.0})
    assert tilted.signal("robots/cartpole/solids/pole/pitch") == pytest.approx(0.17453292519943295)


def test_errors_are_python_exceptions_with_the_location():
    with pytest.raises(s2sim.SceneError) as e:
        s2sim.Simulation(os.path.join(SOURCE, "scenes", "no_such_scene"))
    assert e.value.kind == "scene" and "not found" in str(e.value)
    assert isinstance(e.value, s2sim.Error) and isinstance(e.value, RuntimeError)

    sim = s2sim.Simulation(NXT)
    with pytest.raises(s2sim.UsageError) as e:
        sim.signal("robots/nxt/xx")
    assert "did you mean" in e.value.message and e.value.kind == "usage"
    with pytest.raises(s2sim.UsageError):
        sim.set_input("robots/nxt/axes/right/ref_voltag", 1.0)
    with pytest.raises(s2sim.UsageError):
        sim.set_input(RIGHT, float("nan"))
    with pytest.raises(s2sim.UsageError):
        sim.signals("nothing/matches/*")
    with pytest.raises(s2sim.UsageError):
        sim.signals(["time", "robots/nxt/nope"])
    with pytest.raises(s2sim.UsageError):
        sim.body_pose("robots/nobody")
    with pytest.raises(s2sim.UsageError):
        sim.step(-1)
    with pytest.raises(s2sim.UsageError):  # a layout of another scene
        sim.restore(s2sim.Simulation(CARTPOLE).save())


def test_a_located_scene_error_names_file_element_attribute(tmp_path):
    scene = tmp_path / "scene.xml"
    scene.write_text("<scene><s2sim><physics step_ms='-1'/></s2sim></scene>")
    with pytest.raises(s2sim.SceneError) as e:
        s2sim.Simulation(str(tmp_path))
    assert e.value.file.endswith("scene.xml") and e.value.attribute == "step_ms"
    assert str(e.value).startswith(e.value.file)


def test_a_plugin_error_is_a_plugin_error(tmp_path):
    (tmp_path / "scene.xml").write_text(
        "<scene><plugin kind='no_such_kind'/></scene>")
    with pytest.raises(s2sim.PluginError) as e:
        s2sim.Simulation(str(tmp_path))
    assert "no_such_kind" in str(e.value)


def test_the_gil_is_released_while_stepping():
    sim = s2sim.Simulation(NXT)
    drive(sim)
    stamps = []
    stop = threading.Event()

    def tick():  # wakes up every millisecond; needs the GIL each time
        while not stop.is_set():
            stamps.append(time.perf_counter())
            time.sleep(0.001)

    thread = threading.Thread(target=tick)
    thread.start()
    time.sleep(0.01)
    start = time.perf_counter()
    sim.step(80000)  # 80 s simulated: a few tenths of a second even on a fast machine
    end = time.perf_counter()
    stop.set()
    thread.join()
    assert end - start > 0.1, "the step is too short to tell"
    inside = [t for t in stamps if start + 0.02 < t < end - 0.02]
    # Held through the step, the GIL would let the thread run only before and after it: none
    # inside. Released, it wakes about every millisecond (fewer on a loaded machine).
    assert len(inside) >= 5, (len(inside), end - start)


def test_a_simulation_used_from_two_threads_at_once_refuses_the_second_call():
    sim = s2sim.Simulation(NXT)
    drive(sim)
    refused = []
    stepping = threading.Event()
    done = threading.Event()

    def long_step():
        stepping.set()
        sim.step(60000)
        done.set()

    thread = threading.Thread(target=long_step)
    thread.start()
    stepping.wait()
    while not done.is_set() and len(refused) < 3:
        # Each call either runs between the other thread's calls or is refused while it steps:
        # never a torn state or a crash.
        for call in (lambda: sim.step(1), lambda: sim.signal("time"), lambda: sim.body_pose(1)):
            try:
                call()
            except s2sim.UsageError as e:
                refused.append(str(e))
        time.sleep(0.001)
    thread.join()
    assert refused, "the long step ended before a second call could be tried"
    assert all("in use by another thread" in m and "step()" in m for m in refused), refused
    assert sim.tick >= 60000  # the long step ran whole, beside the single steps let through
    sim.step(1)  # free again once the long step returned


def test_separate_simulations_step_on_separate_threads_as_they_do_alone():
    def run(out, index):
        sim = s2sim.Simulation(NXT, seed=7)
        drive(sim, 4.0 + index)
        sim.step(3000)
        out[index] = sim.signals("*")

    alone = [None, None]
    for i in range(2):
        run(alone, i)
    together = [None, None]
    threads = [threading.Thread(target=run, args=(together, i)) for i in range(2)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    for i in range(2):
        assert np.array_equal(alone[i], together[i])


ROBOTS_4 = os.path.join(SOURCE, "bench", "peers", "scenes", "robots_4")


def robots_4_signals(**options):
    """Every signal of four robots driven 0.3 s at 4 V right, -3 V left, loaded with options."""
    sim = s2sim.Simulation(ROBOTS_4, **options)
    for name in sim.list_inputs():
        if name.endswith("/ref_voltage"):
            sim.set_input(name, 4.0 if "right" in name else -3.0)
    sim.step(300)
    return sim.signals("*")


@pytest.mark.skipif((os.cpu_count() or 1) < 2, reason="one hardware thread")
def test_threads_keyword_gives_the_same_run():
    runs = [robots_4_signals(threads=threads) for threads in (1, 2)]
    assert np.array_equal(runs[0], runs[1])
    assert runs[0].size > 50
    with pytest.raises(Exception, match="threads"):
        s2sim.Simulation(ROBOTS_4, threads=0)


@pytest.mark.skipif((os.cpu_count() or 1) < 2, reason="one hardware thread")
def test_run_ahead_keyword_gives_the_same_run_and_counts_its_stretches():
    ahead = s2sim.Simulation(ROBOTS_4, threads=2)
    lockstep = s2sim.Simulation(ROBOTS_4, threads=2, run_ahead=False)
    for sim in (ahead, lockstep):
        for name in sim.list_inputs():
            if name.endswith("/ref_voltage"):
                sim.set_input(name, 4.0)
        sim.step(300)
    assert np.array_equal(ahead.signals("*"), lockstep.signals("*"))
    assert ahead.run_ahead_counts["stretches"] > 0
    assert ahead.run_ahead_counts["ticks"] >= 200
    assert lockstep.run_ahead_counts == {"stretches": 0, "ticks": 0, "lost": 0}


def test_check_dynamics_keyword_compares_every_substep_and_changes_nothing():
    checked = s2sim.Simulation(ROBOTS_4, check_dynamics=True)
    plain = s2sim.Simulation(ROBOTS_4)
    assert (checked.dynamics, plain.dynamics) == ("checked", "tree")
    for sim in (checked, plain):
        for name in sim.list_inputs():
            if name.endswith("/ref_voltage"):
                sim.set_input(name, 4.0)
        sim.step(200)
    assert np.array_equal(checked.signals("*"), plain.signals("*"))
    check = checked.dynamics_check
    assert check["compared"] == 200
    assert 0 < check["worst_relative"] <= check["agreement"] == 1e-9
    assert plain.dynamics_check["compared"] == 0


def test_simbody_dynamics_keyword_gives_the_fast_paths_run_to_rounding():
    runs = [robots_4_signals(simbody_dynamics=simbody) for simbody in (False, True)]
    assert not np.array_equal(runs[0], runs[1])  # two computations, not one
    assert np.allclose(runs[0], runs[1], rtol=1e-9, atol=1e-9)
