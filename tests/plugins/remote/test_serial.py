"""The serial controller (plugins/remote/serial.cpp) on a pty pair: the test opens the published
device as firmware would, reads the signal lines and writes input lines."""

import os
import select
import threading
import time
import tty

import pytest

import s2sim

SERIAL = os.path.join(os.path.dirname(__file__), "fixtures", "serial")
FORCE = "robots/cartpole/axes/slide/ref_torque"
UART = "controllers/uart/"


def open_device(sim):
    path = "/dev/pts/%d" % int(sim.signal(UART + "pty"))
    fd = os.open(path, os.O_RDWR | os.O_NOCTTY | os.O_NONBLOCK)
    tty.setraw(fd)
    return fd


def read_lines(fd):
    data = b""
    while True:
        try:
            chunk = os.read(fd, 65536)
        except BlockingIOError:
            break
        if not chunk:
            break
        data += chunk
    return data.decode().splitlines()


def test_signal_lines_every_period_and_input_lines_applied():
    sim = s2sim.Simulation(SERIAL)
    fd = open_device(sim)
    try:
        sim.step(60)  # three control periods: three lines
        lines = read_lines(fd)
        assert [l.split()[0] for l in lines] == ["S", "S", "S"]
        times = [float(l.split()[1]) for l in lines]
        assert times == pytest.approx([0.0, 0.02, 0.04])
        assert len(lines[0].split()) == 2 + 2  # S, time, two signals

        os.write(fd, b"?\n")
        sim.step(20)
        lines = read_lines(fd)
        assert "# input robots/cartpole/axes/slide/ref_torque N" in lines
        assert "# signal robots/cartpole/solids/pole/pitch rad" in lines and "# end" in lines

        os.write(fd, b"I 2.5\r\n")
        sim.step(20)
        assert sim.input(FORCE) == 2.5 and sim.signal(UART + "link") == 1
        sim.step(200)
        x = float(read_lines(fd)[-1].split()[2])
        assert x > 0  # driven toward +x
        assert sim.signal(UART + "received") == 2 and sim.signal(UART + "dropped") == 0
    finally:
        os.close(fd)


def test_malformed_lines_are_dropped_and_counted():
    sim = s2sim.Simulation(SERIAL)
    fd = open_device(sim)
    try:
        bad = [b"I\n", b"I 1 2\n", b"I nan\n", b"I 1e999\n", b"X 1\n", b"I1\n", b"\n",
               b"I " + b"1" * 5000 + b"\n", b"I 1 junk\n"]
        for line in bad:
            os.write(fd, line)
            sim.step(20)
        assert sim.signal(UART + "dropped") == len(bad)
        assert sim.input(FORCE) == 0.0 and sim.signal(UART + "received") == 0
    finally:
        os.close(fd)


def test_input_lines_ending_in_lf_cr_or_crlf_are_applied_alike():
    sim = s2sim.Simulation(SERIAL)
    fd = open_device(sim)
    try:
        # The CR LF one split over two writes: its LF is no second, empty line.
        for chunks, value in [([b"I 1.5\n"], 1.5), ([b"I 2.5\r"], 2.5), ([b"I 3.5\r\n"], 3.5),
                              ([b"I 4.5\r", b"\n"], 4.5), ([b"I 5.5\rI 6.5\nI 7.5\r\n"], 7.5)]:
            for chunk in chunks:
                os.write(fd, chunk)
                sim.step(20)
            assert sim.input(FORCE) == value, chunks
        assert sim.signal(UART + "received") == 7 and sim.signal(UART + "dropped") == 0
    finally:
        os.close(fd)


def test_inputs_zeroed_after_the_timeout():
    sim = s2sim.Simulation(SERIAL)
    fd = open_device(sim)
    try:
        os.write(fd, b"I 3\n")
        sim.step(20)
        assert sim.input(FORCE) == 3.0
        time.sleep(0.4)
        sim.step(20)
        assert sim.input(FORCE) == 0.0 and sim.signal(UART + "timeouts") == 1
    finally:
        os.close(fd)


def test_link_name(tmp_path):
    scene = open(os.path.join(SERIAL, "scene.xml")).read()
    scene = scene.replace("../../../../../scenes", os.path.join(os.environ.get(
        "S2SIM_SOURCE_DIR", os.getcwd()), "scenes"))
    link = tmp_path / "ttyS2SIM"
    (tmp_path / "scene.xml").write_text(scene.replace("announce='0'", "announce='0' link='%s'" % link))
    sim = s2sim.Simulation(str(tmp_path))
    assert os.path.realpath(link) == "/dev/pts/%d" % int(sim.signal(UART + "pty"))
    del sim
    assert not os.path.lexists(link)  # removed with the simulation


def serial_scene(tmp_path, attributes):
    """The fixture with its link's timeout_s attribute replaced by `attributes`."""
    scene = open(os.path.join(SERIAL, "scene.xml")).read()
    scene = scene.replace("../../../../../scenes", os.path.join(os.environ.get(
        "S2SIM_SOURCE_DIR", os.getcwd()), "scenes"))
    assert "timeout_s='timeout_s'" in scene
    (tmp_path / "scene.xml").write_text(scene.replace("timeout_s='timeout_s'", attributes))
    return str(tmp_path)


def test_lockstep_takes_one_input_line_a_period(tmp_path):
    sim = s2sim.Simulation(serial_scene(tmp_path, "mode='lockstep' wait_s='5'"))
    fd = open_device(sim)
    try:
        # Three lines at once: each period takes the next, the rest waits for its period.
        os.write(fd, b"I 1\nI 2\r\nI 3\n")
        seen = []
        for _ in range(3):
            sim.step(20)
            seen.append(sim.input(FORCE))
        assert seen == [1.0, 2.0, 3.0]
        lines = read_lines(fd)
        assert [float(l.split()[1]) for l in lines] == pytest.approx([0.0, 0.02, 0.04])
        assert sim.signal(UART + "received") == 3 and sim.signal(UART + "timeouts") == 0
        # A "?" is answered within the wait (after the period's line), which goes on for the
        # input line.
        os.write(fd, b"?\nI 4\n")
        sim.step(20)
        lines = read_lines(fd)
        assert lines[0][:2] == "S " and lines[1] == "# s2sim-serial 1" and lines[-1] == "# end"
        assert sim.input(FORCE) == 4.0 and sim.signal(UART + "received") == 5
    finally:
        os.close(fd)


def answer_every_line(fd, stop):
    """A device that answers every S line with I = -20 * cart position (on its own thread)."""
    pending = b""
    while not stop.is_set():
        ready, _, _ = select.select([fd], [], [], 0.05)
        if not ready:
            continue
        pending += os.read(fd, 65536)
        *lines, pending = pending.split(b"\n")
        for line in lines:
            if line.startswith(b"S "):
                os.write(fd, b"I %.17g\n" % (1.0 - 20.0 * float(line.split()[2])))


def test_lockstep_waits_for_a_device_so_two_runs_are_identical(tmp_path):
    runs = []
    for k in range(2):
        folder = tmp_path / str(k)
        folder.mkdir()
        sim = s2sim.Simulation(serial_scene(folder, "mode='lockstep' wait_s='10'"))
        fd = open_device(sim)
        stop = threading.Event()
        device = threading.Thread(target=answer_every_line, args=(fd, stop))
        device.start()
        try:
            trace = []
            for _ in range(50):
                sim.step(20)
                trace.append((sim.input(FORCE), sim.signal("robots/cartpole/axes/slide/pos")))
        finally:
            stop.set()
            device.join()
            os.close(fd)
        assert sim.signal(UART + "received") == 50 and sim.signal(UART + "timeouts") == 0
        runs.append(trace)
    assert runs[0] == runs[1]
    assert runs[0][-1][1] != 0.0  # the device's answers moved the cart


def test_lockstep_wait_ends_in_a_counted_timeout_and_the_run_goes_on(tmp_path):
    sim = s2sim.Simulation(serial_scene(tmp_path, "mode='lockstep' wait_s='0.2'"))
    fd = open_device(sim)
    try:
        os.write(fd, b"I 4\n")
        sim.step(20)
        assert sim.input(FORCE) == 4.0 and sim.signal(UART + "link") == 1
        sim.step(20)  # no answer within wait_s: the force is zeroed, the wait counted
        assert sim.input(FORCE) == 0.0 and sim.signal(UART + "link") == 0
        assert sim.signal(UART + "timeouts") == 1
        sim.step(200)  # detached: no more waiting, no more lines, no more timeouts
        assert sim.signal(UART + "timeouts") == 1
        assert len(read_lines(fd)) == 2  # the lines at 0 and 0.02 s
        # A "?" attaches the device again: this period's line follows the description.
        os.write(fd, b"?\nI 5\n")
        sim.step(20)
        lines = read_lines(fd)
        assert lines[-1].split()[1] == "0.23999999999999999" and lines[-2] == "# end"
        assert sim.input(FORCE) == 5.0 and sim.signal(UART + "link") == 1
        sim.step(20)  # attached: waits again, and times out again
        assert sim.signal(UART + "timeouts") == 2
    finally:
        os.close(fd)


def test_an_unattended_run_caps_the_wait_and_a_bad_cap_is_refused(tmp_path, monkeypatch):
    # S2SIM_LINK_WAIT_MAX_S: a CI job's bound on the wait a scene asks for (here a thousand s).
    folder = serial_scene(tmp_path, "mode='lockstep' wait_s='1000'")
    monkeypatch.setenv("S2SIM_LINK_WAIT_MAX_S", "0.05")
    sim = s2sim.Simulation(folder)
    start = time.perf_counter()
    sim.step(100)  # no device: one capped wait, then detached
    assert time.perf_counter() - start < 5.0
    assert sim.signal(UART + "timeouts") == 1 and sim.signal(UART + "link") == 0
    del sim
    for bad in ["0", "-1", "1e300", "nan", "soon"]:
        monkeypatch.setenv("S2SIM_LINK_WAIT_MAX_S", bad)
        with pytest.raises(s2sim.UsageError) as e:
            s2sim.Simulation(folder)
        assert "S2SIM_LINK_WAIT_MAX_S='%s'" % bad in str(e.value), str(e.value)


def flood(fd, stop):
    """A broken device: lines the link drops, as fast as the terminal takes them."""
    while not stop.is_set():
        try:
            os.write(fd, b"X garbage\n" * 400)
        except BlockingIOError:
            time.sleep(0.0005)


def test_lockstep_a_flood_of_other_lines_ends_the_wait_in_a_timeout(tmp_path):
    sim = s2sim.Simulation(serial_scene(tmp_path, "mode='lockstep' wait_s='0.2'"))
    fd = open_device(sim)
    os.set_blocking(fd, False)
    stop = threading.Event()
    device = threading.Thread(target=flood, args=(fd, stop))
    device.start()
    try:
        sim.step(20)  # waits no longer than wait_s, however many lines come
        assert sim.signal(UART + "timeouts") == 1 and sim.signal(UART + "dropped") > 0
        sim.step(200)  # detached: a bounded read of the flood each period, no waiting
        assert sim.signal(UART + "timeouts") == 1 and sim.signal(UART + "received") == 0
    finally:
        stop.set()
        device.join()
        os.close(fd)


@pytest.mark.parametrize("attributes, attribute, says", [
    ("mode='lockstep' timeout_s='1'", "timeout_s", "applies in mode='realtime' only"),
    ("wait_s='1'", "wait_s", "applies in mode='lockstep' only"),
    ("mode='lockstep' wait_s='0'", "wait_s", ""),
    ("mode='lockstep' wait_s='-2'", "wait_s", ""),
    ("mode='lockstep' wait_s='1e300'", "wait_s", "86400"),
    ("mode='lockstep' wait_s='forever'", "wait_s", ""),
    ("mode='lock-step'", "mode", "lockstep"),
    ("mode='lockstep' wiat_s='1'", "wiat_s", "wait_s"),
    ("timeout_s='0'", "timeout_s", ""),
    ("period_s='0'", "period_s", ""),
])
def test_a_bad_parameter_is_a_located_error(tmp_path, attributes, attribute, says):
    with pytest.raises(s2sim.SceneError) as e:
        s2sim.Simulation(serial_scene(tmp_path, attributes))
    assert str(e.value).startswith("scene.xml: scene/plugin@%s: " % attribute), str(e.value)
    assert says in e.value.message, str(e.value)
