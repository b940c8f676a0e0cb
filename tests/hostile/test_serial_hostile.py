"""The serial link against careless or hostile use: control bytes inside a line, and a `link=`
path that names a file S2Sim did not make."""

import os
import tty

import pytest

import s2sim

SOURCE = os.environ.get("S2SIM_SOURCE_DIR", os.getcwd())
SERIAL = os.path.join(SOURCE, "tests", "plugins", "remote", "fixtures", "serial")
FORCE = "robots/cartpole/axes/slide/ref_torque"
UART = "controllers/uart/"


def open_device(sim):
    fd = os.open("/dev/pts/%d" % int(sim.signal(UART + "pty")),
                 os.O_RDWR | os.O_NOCTTY | os.O_NONBLOCK)
    tty.setraw(fd)
    return fd


def with_link(tmp_path, link):
    """The serial fixture with link='<link>' on its plugin, written beside it."""
    text = open(os.path.join(SERIAL, "scene.xml")).read()
    text = text.replace("kind='serial'", "kind='serial' link='%s'" % link, 1)
    cartpole = os.path.normpath(os.path.join(SOURCE, "scenes", "cartpole", "cartpole.xml"))
    text = text.replace("file='../../../../../scenes/cartpole/cartpole.xml'", "file='%s'" % cartpole)
    (tmp_path / "scene.xml").write_text(text)
    return str(tmp_path)


def test_a_line_with_a_nul_or_control_byte_is_dropped_not_cut_short():
    # Before: "I 0.3<NUL>garbage" was read as "I 0.3".
    sim = s2sim.Simulation(SERIAL)
    fd = open_device(sim)
    try:
        for line in (b"I 0.3\x00garbage\n", b"I 0.4\x1b\n", b"I\x7f 0.5\n"):
            os.write(fd, line)
            sim.step(20)
            assert sim.input(FORCE) == 0.0, line
        os.write(fd, b"I 0.6\t\n")  # a tab is a blank
        sim.step(20)
        assert sim.input(FORCE) == 0.6
        assert sim.signal(UART + "dropped") == 3 and sim.signal(UART + "received") == 1
    finally:
        os.close(fd)


def test_link_never_replaces_a_file_it_did_not_make(tmp_path):
    # Before: link= deleted whatever was at the path, at load and again at exit.
    precious = tmp_path / "ttyS2SIM"
    precious.write_text("my notes\n")
    with pytest.raises(s2sim.SceneError, match="exists and is not a link to a pseudo-terminal"):
        s2sim.Simulation(with_link(tmp_path, str(precious)))
    assert precious.read_text() == "my notes\n"
    elsewhere = tmp_path / "elsewhere"
    os.symlink("/etc/hostname", elsewhere)
    with pytest.raises(s2sim.SceneError, match="not a link to a pseudo-terminal"):
        s2sim.Simulation(with_link(tmp_path, str(elsewhere)))
    assert os.readlink(elsewhere) == "/etc/hostname"


def test_link_replaces_a_stale_pseudo_terminal_link_and_removes_its_own(tmp_path):
    stale = tmp_path / "ttyS2SIM"
    os.symlink("/dev/pts/999999", stale)  # a previous run's, left by a kill
    sim = s2sim.Simulation(with_link(tmp_path, str(stale)))
    assert os.readlink(stale) == "/dev/pts/%d" % int(sim.signal(UART + "pty"))
    del sim
    assert not os.path.lexists(stale)
