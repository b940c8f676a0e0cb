"""Every input has a valid range (docs/plugins.md, "Input ranges"): a value outside it from a
remote peer is dropped and counted, from Python it is an error naming the input, from a script
a script error naming the call and its line, and in a scene a located error. Before, a force
of 1e30 N from any of them was applied (the cart ended at 2.1e25 m, exit 0)."""

import math
import os
import shutil
import socket
import subprocess

import pytest

import s2sim
from s2sim import remote

SOURCE = os.environ.get("S2SIM_SOURCE_DIR", os.getcwd())
RUNNER = os.path.join(os.environ.get("S2SIM_BIN_DIR", os.path.join(SOURCE, "build", "bin")),
                      "s2sim-run")
CARTPOLE = os.path.join(SOURCE, "scenes", "cartpole")
REALTIME = os.path.join(SOURCE, "tests", "plugins", "remote", "fixtures", "realtime")
FORCE = "robots/cartpole/axes/slide/ref_torque"
LINK = "controllers/link/"


def test_python_refuses_a_value_outside_the_range_naming_the_input():
    sim = s2sim.Simulation(CARTPOLE)
    sim.set_input(FORCE, 1e8)  # the sanity bound of a force, included
    for bad in (1e30, -1e30, math.nan, math.inf):
        with pytest.raises(s2sim.UsageError) as e:
            sim.set_input(FORCE, bad)
        assert FORCE in str(e.value) and "[-100000000, 100000000] N" in str(e.value)
    assert sim.input(FORCE) == 1e8
    # A range the component declares: friction is never negative.
    with pytest.raises(s2sim.UsageError) as e:
        sim.set_input("robots/cartpole/axes/slide/friction_fc", -1)
    assert "friction_fc" in str(e.value) and "[0, " in str(e.value)


def test_a_remote_peer_out_of_range_is_dropped_and_counted():
    sim = s2sim.Simulation(REALTIME)
    port = int(sim.signal(LINK + "port"))
    with remote.Client(port=port) as link:
        link.send([2.0])
        sim.step(20)
        assert sim.input(FORCE) == 2.0
        link.send([1e30])
        sim.step(20)
        assert sim.input(FORCE) == 2.0, "an input out of its range was applied"
        assert sim.signal(LINK + "dropped") == 1
        link.send([3.0])
        sim.step(20)
        assert sim.input(FORCE) == 3.0


def test_a_scene_value_outside_the_range_is_a_located_error(tmp_path):
    scene = tmp_path / "quadrotor"
    shutil.copytree(os.path.join(SOURCE, "scenes", "quadrotor"), scene)
    robot = scene / "quadrotor.xml"
    text = robot.read_text()
    assert "z_ref='1'" in text
    robot.write_text(text.replace("z_ref='1'", "z_ref='1e12'"))
    with pytest.raises(s2sim.Error) as e:
        s2sim.Simulation(str(scene))
    message = str(e.value)
    assert "quadrotor.xml" in message and "z_ref" in message
    assert "1e+12 is outside its range" in message


@pytest.mark.skipif(shutil.which("fpc") is None, reason="no fpc")
def test_a_script_out_of_range_is_a_script_error_naming_the_call_and_its_line(tmp_path):
    script = tmp_path / "control.pas"
    script.write_text("procedure Initialize;\nbegin\nend;\n\nprocedure Control;\nbegin\n"
                      "  SetAxisTorqueRef(0, 0, 1e30);\nend;\n")
    with socket.socket(socket.AF_INET, socket.SOCK_DGRAM) as s:
        s.bind(("127.0.0.1", 0))
        port = s.getsockname()[1]
    env = dict(os.environ, S2SIM_PASCAL_CACHE=str(tmp_path / "cache"), S2SIM_UDP_PORT=str(port))
    done = subprocess.run([RUNNER, CARTPOLE, "--script", str(script), "--duration", "0.5",
                           "--quiet", "--no-timing"], env=env, capture_output=True, text=True,
                          timeout=300)
    assert done.returncode == 0, done.stderr  # the script stops, the simulation goes on
    assert "SetAxisTorqueRef: set_input: input '" + FORCE + "'" in done.stderr, done.stderr
    assert "1e+30 is outside its range" in done.stderr
    assert "control.pas:7" in done.stderr
