"""The serial controller (plugins/remote/serial.cpp) on a pty pair: the test opens the published
device as firmware would, reads the signal lines and writes input lines."""

import os
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
