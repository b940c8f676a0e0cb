"""The remote controller (plugins/remote) with the pure-Python client (s2sim.remote), in both
modes: lock-step in-process (the simulation steps in a thread with the GIL released) and against
the runner with the cart-pole example (determinism), real-time with its timeout."""

import filecmp
import os
import socket
import struct
import subprocess
import sys
import threading
import time

import pytest

import s2sim
from announced_runner import start_announced_runner
from s2sim import remote

SOURCE = os.environ.get("S2SIM_SOURCE_DIR", os.getcwd())
BIN = os.environ.get("S2SIM_BIN_DIR", os.path.join(SOURCE, "build", "bin"))
CARTPOLE = os.path.join(SOURCE, "scenes", "cartpole_remote")
REALTIME = os.path.join(os.path.dirname(__file__), "fixtures", "realtime")
FORCE = "robots/cartpole/axes/slide/ref_torque"
LINK = "controllers/link/"


def lockstep_sim(wait_s=5.0):
    return s2sim.Simulation(CARTPOLE, defines={"remote_port": 0, "remote_wait_s": wait_s})


def in_thread(fn, *args):
    thread = threading.Thread(target=fn, args=args)
    thread.start()
    return thread


def test_lockstep_advances_one_period_per_request():
    sim = lockstep_sim()
    port = int(sim.signal(LINK + "port"))
    period_ticks = int(round(sim.control_period / sim.tick_s))
    runner = in_thread(sim.step, 5 * period_ticks)  # blocks on the link at every period
    with remote.Client(port=port) as link:
        info = link.hello()
        assert info.mode == "lockstep" and info.period == pytest.approx(0.02)
        assert info.inputs == [FORCE]
        assert info.signals[0] == "robots/cartpole/axes/slide/pos"
        t, y = link.observe()
        assert t == 0.0 and len(y) == 4
        times = []
        for k in range(4):
            t, y = link.step([1.0])
            times.append(t)
        assert times == pytest.approx([0.02, 0.04, 0.06, 0.08])
        assert y[0] > 0  # pushed toward +x
        link.send([0.0])  # the fifth period's request: the simulation ends its step(n)
    runner.join(10)
    assert not runner.is_alive()
    assert sim.signal(LINK + "received") == 7  # hello, observe, 5 inputs
    assert sim.signal(LINK + "dropped") == 0 and sim.signal(LINK + "link") == 1


def test_lockstep_stale_and_repeated_requests():
    sim = lockstep_sim()
    port = int(sim.signal(LINK + "port"))
    period_ticks = int(round(sim.control_period / sim.tick_s))
    runner = in_thread(sim.step, 3 * period_ticks)
    with remote.Client(port=port) as link:
        link.hello()
        link.sequence = 10
        t1, _ = link.step([0.5])  # sequence 11
        # The same request again (a lost reply): answered, not advanced.
        link.socket.sendto(remote.pack(remote.INPUTS, 11, remote.pack_doubles([0.5])), link.address)
        seq, payload = link._wait(remote.SIGNALS, 11, 5.0)
        assert struct.unpack_from("<d", payload)[0] == t1
        # An older one: stale, dropped and counted.
        link.socket.sendto(remote.pack(remote.INPUTS, 3, remote.pack_doubles([9.0])), link.address)
        t2, _ = link.step([0.5])  # sequence 12
        assert t2 == pytest.approx(t1 + 0.02)
        link.send([0.0])
    runner.join(10)
    assert sim.signal(LINK + "stale") == 1 and sim.signal(LINK + "dropped") == 1
    assert sim.input(FORCE) == 0.0


def test_lockstep_without_a_client_runs_on_with_zero_inputs():
    sim = lockstep_sim(wait_s=0.05)
    sim.set_input(FORCE, 3.0)
    start = time.perf_counter()
    sim.run_until(1.0)  # waits once, then no more
    assert time.perf_counter() - start < 1.0
    assert sim.input(FORCE) == 0.0 and sim.signal(LINK + "link") == 0


def test_an_unattended_run_caps_the_lockstep_wait(monkeypatch):
    monkeypatch.setenv("S2SIM_LINK_WAIT_MAX_S", "0.05")
    sim = lockstep_sim(wait_s=1000.0)  # without the cap, a thousand seconds for a client
    start = time.perf_counter()
    sim.run_until(1.0)
    assert time.perf_counter() - start < 5.0
    assert sim.signal(LINK + "link") == 0  # waited once, 50 ms, for no client


def run_cartpole_once(tmp_path, tag):
    sim_log, client_log = tmp_path / ("sim_%s.csv" % tag), tmp_path / ("client_%s.csv" % tag)
    runner, port = start_announced_runner(
        [os.path.join(BIN, "s2sim-run"), CARTPOLE, "--duration", "4", "--define",
         "remote_port=0", "--log", str(sim_log), "--signals", "robots/cartpole/*", "--quiet"])
    client = subprocess.run(
        [sys.executable, os.path.join(SOURCE, "python", "examples", "cartpole_remote.py"),
         "--port", str(port), "--duration", "4", "--log", str(client_log)],
        capture_output=True, text=True, timeout=120)
    assert runner.wait(timeout=120) == 0, runner.stderr.read()
    assert client.returncode == 0, client.stdout + client.stderr  # balanced
    return sim_log, client_log


def test_lockstep_runs_are_identical_and_balance_the_pole(tmp_path):
    a = run_cartpole_once(tmp_path, "a")
    b = run_cartpole_once(tmp_path, "b")
    assert filecmp.cmp(a[0], b[0], shallow=False), "simulation logs differ"
    assert filecmp.cmp(a[1], b[1], shallow=False), "client logs differ"
    assert len(open(a[0]).read().splitlines()) > 4000


def start_cartpole_runner(duration_s):
    """s2sim-run on the lock-step cart-pole with a port the system picks; (process, port)."""
    return start_announced_runner(
        [os.path.join(BIN, "s2sim-run"), CARTPOLE, "--duration", str(duration_s), "--define",
         "remote_port=0", "--quiet"])


def test_a_lockstep_client_sees_the_end_of_the_run_and_stops():
    """A client that does not know --duration steps until the simulation says END: the last
    reply is the last control period's (0.48 s of a 0.5 s run), then RunEnded, not a timeout."""
    runner, port = start_cartpole_runner(0.5)
    times = []
    with remote.Client(port=port, timeout=60) as link:
        link.hello()
        with pytest.raises(remote.RunEnded) as ended:
            while True:
                t, _ = link.step([0.0])
                times.append(t)
    assert runner.wait(timeout=60) == 0, runner.stderr.read()
    assert times == pytest.approx([0.02 * k for k in range(1, 25)])
    assert ended.value.time == pytest.approx(0.48)
    assert "ended" in str(ended.value)


def test_the_c_client_sees_the_end_of_the_run(tmp_path):
    source = tmp_path / "until_end.c"
    source.write_text(r'''
#include "s2sim_remote.h"
#include <stdio.h>
#include <stdlib.h>
int main(int argc, char** argv) {
  s2sim_remote_client c;
  double t = -1, y[8], u = 0.0;
  int n, replies = 0;
  if (argc < 2 || s2sim_remote_open(&c, "127.0.0.1", (uint16_t)atoi(argv[1])) != 0) return 2;
  while ((n = s2sim_remote_step(&c, &u, 1, &t, y, 8, 60000)) >= 0) ++replies;
  printf("%d %d %.6f\n", replies, n, t);
  s2sim_remote_close(&c);
  return n == -3 ? 0 : 1;
}
''')
    exe = tmp_path / "until_end"
    subprocess.run(["cc", "-std=c99", "-Wall", "-Wextra", "-Werror", "-D_POSIX_C_SOURCE=200809L",
                    "-I", os.path.join(SOURCE, "plugins", "remote", "include"), str(source),
                    "-o", str(exe)], check=True)
    runner, port = start_cartpole_runner(0.3)
    out = subprocess.run([str(exe), str(port)], capture_output=True, text=True, timeout=120)
    assert runner.wait(timeout=60) == 0, runner.stderr.read()
    assert out.returncode == 0, out.stdout + out.stderr
    replies, status, t = out.stdout.split()
    assert (int(replies), int(status), float(t)) == (14, -3, pytest.approx(0.28))


def pace(sim, seconds, period_s=0.02):
    """Steps the simulation in control periods at about real time, for `seconds` of wall time."""
    ticks = int(round(period_s / sim.tick_s))
    end = time.perf_counter() + seconds
    while time.perf_counter() < end:
        sim.step(ticks)
        time.sleep(period_s)


def test_realtime_sends_every_period_and_applies_inputs():
    sim = s2sim.Simulation(REALTIME)
    port = int(sim.signal(LINK + "port"))
    with remote.Client(port=port, timeout=2.0) as link:
        link.socket.sendto(remote.pack(remote.HELLO, 1), link.address)
        sim.step(20)  # the controller reads at its period, never waits
        _, payload = link._wait(remote.DESCRIBE, 1, 2.0)
        info = remote.Description(payload.decode())
        assert info.mode == "realtime" and info.inputs == [FORCE]
        link.sequence = 1
        link.send([2.5])
        sim.step(20)
        assert sim.input(FORCE) == 2.5 and sim.signal(LINK + "link") == 1
        t, y = link.receive()
        assert t == pytest.approx(sim.time - 0.02, abs=1e-9) and len(y) == 2


def test_realtime_zeroes_the_inputs_after_the_timeout():
    sim = s2sim.Simulation(REALTIME, defines={"timeout_s": 0.3})
    port = int(sim.signal(LINK + "port"))
    with remote.Client(port=port) as link:
        link.send([4.0])
        pace(sim, 0.1)
        assert sim.input(FORCE) == 4.0
        link.send([4.0])  # then the client stops sending
        pace(sim, 0.15)
        assert sim.input(FORCE) == 4.0, "zeroed before the timeout"
        pace(sim, 0.4)
        assert sim.input(FORCE) == 0.0 and sim.signal(LINK + "link") == 0
        assert sim.signal(LINK + "timeouts") == 1
        link.send([1.0])  # the link comes back
        pace(sim, 0.05)
        assert sim.input(FORCE) == 1.0 and sim.signal(LINK + "link") == 1


def test_non_local_address_is_refused_unless_allowed(tmp_path):
    scene = open(os.path.join(REALTIME, "scene.xml")).read()
    scene = scene.replace("../../../../../scenes", os.path.join(SOURCE, "scenes"))
    (tmp_path / "scene.xml").write_text(scene.replace("announce='0'", "announce='0' address='0.0.0.0'"))
    with pytest.raises(s2sim.SceneError) as e:
        s2sim.Simulation(str(tmp_path))
    assert e.value.attribute == "address" and "allow_remote" in e.value.message
    (tmp_path / "link.key").write_bytes(b"a key of at least sixteen bytes")
    (tmp_path / "scene.xml").write_text(scene.replace(
        "announce='0'", "announce='0' address='0.0.0.0' allow_remote='1' key_file='%s'" %
        (tmp_path / "link.key")))
    s2sim.Simulation(str(tmp_path))


@pytest.mark.parametrize("written, attributes, attribute", [
    # Past a day: a hang, and a clock's overflow.
    ("mode='realtime'", "mode='lockstep' wait_s='1e300'", "wait_s"),
    ("timeout_s='timeout_s'", "timeout_s='1e300'", "timeout_s"),
])
def test_a_wait_past_a_day_is_a_located_error(tmp_path, written, attributes, attribute):
    scene = open(os.path.join(REALTIME, "scene.xml")).read()
    scene = scene.replace("../../../../../scenes", os.path.join(SOURCE, "scenes"))
    assert written in scene
    (tmp_path / "scene.xml").write_text(scene.replace(written, attributes))
    with pytest.raises(s2sim.SceneError) as e:
        s2sim.Simulation(str(tmp_path))
    assert e.value.attribute == attribute and "86400" in e.value.message, str(e.value)


def test_a_pattern_that_matches_nothing_is_a_located_error(tmp_path):
    scene = open(os.path.join(REALTIME, "scene.xml")).read()
    scene = scene.replace("../../../../../scenes", os.path.join(SOURCE, "scenes"))
    (tmp_path / "scene.xml").write_text(scene.replace("robots/cartpole/axes/slide/ref_torque'",
                                                      "robots/cartpole/axes/nope/*'"))
    with pytest.raises(s2sim.SceneError) as e:
        s2sim.Simulation(str(tmp_path))
    assert e.value.attribute == "inputs" and "matches no input" in e.value.message


def test_c_client_header_compiles_and_talks(tmp_path):
    """The header-only C client against the lock-step cart-pole, compiled with cc."""
    source = tmp_path / "client.c"
    source.write_text(r'''
#include "s2sim_remote.h"
#include <stdio.h>
#include <stdlib.h>
int main(int argc, char** argv) {
  s2sim_remote_client c;
  double t = -1, y[8], u = 1.0;
  int i, n = 0;
  if (argc < 2) return 2;
  if (s2sim_remote_open(&c, "127.0.0.1", (uint16_t)atoi(argv[1])) != 0) return 2;
  for (i = 0; i < 3; ++i) n = s2sim_remote_step(&c, &u, 1, &t, y, 8, 5000);
  u = 0;
  s2sim_remote_send(&c, S2SIM_REMOTE_INPUTS, &u, 1);
  printf("%d %.6f %.9f\n", n, t, y[0]);
  s2sim_remote_close(&c);
  return n == 4 ? 0 : 1;
}
''')
    exe = tmp_path / "client"
    subprocess.run(["cc", "-std=c99", "-Wall", "-Wextra", "-Werror", "-D_POSIX_C_SOURCE=200809L",
                    "-I", os.path.join(SOURCE, "plugins", "remote", "include"), str(source),
                    "-o", str(exe)], check=True)
    sim = lockstep_sim()
    port = int(sim.signal(LINK + "port"))  # before the step: a stepping Simulation takes no call
    runner = in_thread(sim.step, 4 * 20)
    out = subprocess.run([str(exe), str(port)], capture_output=True, text=True, timeout=30)
    runner.join(10)
    assert out.returncode == 0, out.stdout + out.stderr
    n, t, x = out.stdout.split()
    assert float(t) == pytest.approx(0.06) and float(x) > 0


def test_robot_level_link_serves_the_whole_robot_by_default(tmp_path):
    """Placed in a robot file, the link serves robots/<robot>/*: the kernel's signals and
    inputs, and the drive train's (configured before the controller plugins, SDK 0.7), but not
    its own counters."""
    robot = open(os.path.join(SOURCE, "scenes", "cartpole", "cartpole.xml")).read()
    robot = robot.replace("</robot>", "  <plugin kind='remote' id='link' port='0' announce='0'/>\n</robot>")
    (tmp_path / "cartpole.xml").write_text(robot)
    (tmp_path / "scene.xml").write_text(
        "<scene><s2sim><control period_ms='20'/></s2sim><robot><ID name='cartpole'/>"
        "<body file='cartpole.xml'/></robot></scene>")
    sim = s2sim.Simulation(str(tmp_path))
    prefix = "robots/cartpole/controllers/link/"
    with remote.Client(port=int(sim.signal(prefix + "port")), timeout=2.0) as link:
        link.socket.sendto(remote.pack(remote.HELLO, 1), link.address)
        sim.step(20)
        _, payload = link._wait(remote.DESCRIBE, 1, 2.0)
    info = remote.Description(payload.decode())
    robot_inputs = [n for n in sim.list_inputs() if n.startswith("robots/cartpole/")]
    assert info.inputs == robot_inputs
    assert "robots/cartpole/axes/slide/ref_voltage" in info.inputs  # the drive train's
    assert "robots/cartpole/axes/slide/current" in info.signals
    assert "robots/cartpole/solids/pole/pitch" in info.signals
    assert not any(s.startswith(prefix) for s in info.signals)
    assert all(s.startswith("robots/cartpole/") for s in info.signals)


def test_the_python_client_is_one_standalone_file(tmp_path):
    """remote.py alone, without the package or any third-party module, drives the link."""
    import shutil

    shutil.copy(remote.__file__, tmp_path / "remote.py")
    sim = lockstep_sim()
    port = int(sim.signal(LINK + "port"))  # before the step: a stepping Simulation takes no call
    runner = in_thread(sim.step, 2 * 20)
    code = ("import sys, remote; c = remote.Client(port=int(sys.argv[1])); d = c.hello(); "
            "t, y = c.step([2.0]); c.send([0.0]); print(d.mode, t, len(y))")
    out = subprocess.run([sys.executable, "-E", "-s", "-c", code, str(port)],
                         cwd=str(tmp_path), capture_output=True, text=True, timeout=30)
    runner.join(10)
    assert out.returncode == 0, out.stderr
    assert out.stdout.split() == ["lockstep", "0.02", "4"]


def test_a_scene_too_large_for_one_datagram_is_refused_with_advice(tmp_path):
    # 400 things with long names: 13 signals each, about 220 kB of DESCRIBE text.
    things = "".join(
        "<cuboid><ID value='a_thing_with_a_rather_long_name_%03d'/><mass value='1'/>"
        "<size x='0.1' y='0.1' z='0.1'/><pos x='%d' y='0' z='0.05'/></cuboid>" % (i, i)
        for i in range(400))
    (tmp_path / "things.xml").write_text("<things>%s</things>" % things)
    (tmp_path / "scene.xml").write_text(
        "<scene><things file='things.xml'/><plugin kind='remote' port='0' announce='0'/></scene>")
    with pytest.raises(s2sim.SceneError) as e:
        s2sim.Simulation(str(tmp_path))
    assert e.value.attribute == "signals" and "do not fit in one datagram" in e.value.message
    assert "narrow them" in e.value.message
