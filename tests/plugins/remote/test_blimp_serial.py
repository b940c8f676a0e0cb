"""The paper's blimp (§4.3) flown over a serial line: examples/blimp_serial's C program, built
with CMake, stands in for the microcontroller and flies scenes/blimp_serial through the serial
controller in lock-step (docs/tutorials/blimp-serial.md). The gondola passes within 0.5 m of
each waypoint, in order, and two runs with the same seed write byte-identical logs, the second
with a pilot slower at every answer."""

import math
import os
import shutil
import subprocess
import tempfile
import time

import pytest

SOURCE = os.environ.get("S2SIM_SOURCE_DIR", os.getcwd())
BIN = os.environ.get("S2SIM_BIN_DIR", os.path.join(SOURCE, "build", "bin"))
CMAKE = os.environ.get("CMAKE_COMMAND", "cmake")
SCENE = os.path.join(SOURCE, "scenes", "blimp_serial")
PILOT = os.path.join(SOURCE, "examples", "blimp_serial")
DURATION_S = 55
GONDOLA = "robots/blimp/solids/gondola/"
UART = "controllers/uart/"
# The pty's number differs from run to run: the rest of the link's signals are logged.
LOGGED = ["robots/*", UART + "received", UART + "dropped", UART + "link", UART + "timeouts"]


@pytest.fixture(scope="module")
def work():
    folder = tempfile.mkdtemp(prefix="s2sim-blimp-serial-%d-" % os.getpid())
    yield folder
    shutil.rmtree(folder, ignore_errors=True)


@pytest.fixture(scope="module")
def pilot(work):
    build = os.path.join(work, "pilot")
    subprocess.run([CMAKE, "-S", PILOT, "-B", build, "-DCMAKE_BUILD_TYPE=Release",
                    "-DCMAKE_C_FLAGS=-Werror"], check=True, capture_output=True)
    subprocess.run([CMAKE, "--build", build], check=True, capture_output=True)
    return os.path.join(build, "blimp_serial_pilot")


def waypoints():
    points = []
    for line in open(os.path.join(SCENE, "waypoints.txt")):
        line = line.split("#")[0].split()
        if line:
            points.append(tuple(float(v) for v in line))
    return points


def fly(work, pilot, name, seed=7, delay_s=0.0):
    """One run: the scene (its device link moved into this process's folder), then the pilot on
    its device, answering each line after `delay_s`. Returns the log's path and the pilot's
    output."""
    scene = os.path.join(work, name)
    os.makedirs(scene)
    device = os.path.join(scene, "tty")
    text = open(os.path.join(SCENE, "scene.xml")).read()
    assert "link='/tmp/ttyS2SIM_blimp'" in text
    with open(os.path.join(scene, "scene.xml"), "w") as f:
        f.write(text.replace("link='/tmp/ttyS2SIM_blimp'", "link='%s'" % device))
    shutil.copy(os.path.join(SCENE, "blimp.xml"), scene)
    log = os.path.join(work, name + ".csv")
    err = open(os.path.join(work, name + ".err"), "w+")
    runner = subprocess.Popen(
        [os.path.join(BIN, "s2sim-run"), scene, "--duration", str(DURATION_S), "--seed",
         str(seed), "--define", "serial_wait_s=10", "--log", log, "--log-period", "0.02", "--signals"] + LOGGED,
        stdout=subprocess.DEVNULL, stderr=err)
    try:
        # The link exists once the scene is loaded; the first control period waits for the pilot.
        for _ in range(3000):
            if os.path.lexists(device) or runner.poll() is not None:
                break
            time.sleep(0.01)
        assert os.path.lexists(device), "no device link; runner: " + open(err.name).read()
        out = subprocess.run([pilot, "--waypoints", os.path.join(SCENE, "waypoints.txt"),
                              "--delay", str(delay_s), "--timeout", "20", device], capture_output=True, text=True,
                             timeout=120)
        assert runner.wait(timeout=120) == 0, open(err.name).read()
    finally:
        if runner.poll() is None:
            runner.kill()
            runner.wait()
        err.close()
    assert out.returncode == 0, out.stdout + out.stderr
    return log, out.stdout


def read_log(path):
    with open(path) as f:
        header = [h.split(" [")[0] for h in f.readline().rstrip("\n").split(",")]
        rows = [[float(v) for v in line.split(",")] for line in f]
    return {name: [r[i] for r in rows] for i, name in enumerate(header)}


def test_the_c_pilot_flies_every_waypoint_and_two_runs_log_the_same(work, pilot, capsys):
    def report(text):  # the figures, shown by ctest -V too
        with capsys.disabled():
            print(text)

    first, said = fly(work, pilot, "first")
    report("\n" + said.rstrip())
    log = read_log(first)
    t, x, y, z = log["time"], log[GONDOLA + "x"], log[GONDOLA + "y"], log[GONDOLA + "z"]
    nearest_times = []
    start = 0
    for k, (wx, wy, wz) in enumerate(waypoints()):
        # In order: each waypoint's nearest pass comes after the previous one's.
        d = [math.dist((x[i], y[i], z[i]), (wx, wy, wz)) for i in range(start, len(t))]
        best = start + min(range(len(d)), key=d.__getitem__)
        report("waypoint %d (%g %g %g): nearest %.3f m at %.2f s" % (k + 1, wx, wy, wz,
                                                                   min(d), t[best]))
        assert min(d) < 0.5
        nearest_times.append(t[best])
        start = best
    assert nearest_times == sorted(nearest_times)
    assert "4 of 4 waypoints reached" in said
    # Lock-step: one input line a control period (the last at 54.98 s) and the pilot's "?",
    # never a timeout.
    assert max(log[UART + "timeouts"]) == 0 and max(log[UART + "dropped"]) == 0
    assert log[UART + "received"][-1] == round(t[-1] / 0.02) + 1

    # The same run with a pilot 1 ms slower at every answer: lock-step waits for it.
    second, said_again = fly(work, pilot, "second", delay_s=0.001)
    assert said_again == said
    with open(first, "rb") as a, open(second, "rb") as b:
        first_bytes, second_bytes = a.read(), b.read()
    report("logs: %d and %d bytes, %s" % (len(first_bytes), len(second_bytes),
                                          "identical" if first_bytes == second_bytes else "differ"))
    assert first_bytes == second_bytes, "two runs with the same seed logged differently"
