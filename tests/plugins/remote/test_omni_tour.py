"""The SimTwo paper's omni robot in the Fire-Fighting arena (scenes/firefighting_omni), driven
and localised by the remote client python/examples/omni_tour.py in lock-step: every room is
reached (by the true pose, from the simulation's own log), the particle filter's estimate stays
within 5 cm RMS of the true pose with the IR noise on, and two runs with the same seeds write
identical logs (docs/tutorials/omni-localisation.md)."""

import filecmp
import importlib.util
import os
import subprocess
import sys
import xml.etree.ElementTree as ET

import numpy as np

from announced_runner import start_announced_runner

SOURCE = os.environ.get("S2SIM_SOURCE_DIR", os.getcwd())
BIN = os.environ.get("S2SIM_BIN_DIR", os.path.join(SOURCE, "build", "bin"))
SCENE = os.path.join(SOURCE, "scenes", "firefighting_omni")
CLIENT = os.path.join(SOURCE, "python", "examples", "omni_tour.py")
DURATION_S = 42  # the tour takes about 38.5 s of simulated time
ROBOT = "robots/omni/"


def room_insides():
    """Each room's inside (x0, y0, x1, y1), m: its rectangle in the arena's generator less the
    walls along its hallway sides."""
    spec = importlib.util.spec_from_file_location(
        "arena", os.path.join(SOURCE, "scripts", "make-firefighting-arena.py"))
    arena = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(arena)
    insides = {}
    for name, (x0, y0, x1, y1, sides, _) in arena.ROOMS.items():
        t = arena.THICK_M
        insides[name] = (x0 + t * ("west" in sides), y0 + t * ("south" in sides),
                         x1 - t * ("east" in sides), y1 - t * ("north" in sides))
    return insides


# The true centre must come this far into a room, past the wall with the door.
DEPTH_M = 0.15


def start_tour(tmp_path, tag):
    """s2sim-run and the client, both running; returns the two processes and the log paths."""
    sim_log, client_log = tmp_path / ("sim_%s.csv" % tag), tmp_path / ("client_%s.csv" % tag)
    runner, port = start_announced_runner(
        # A long wait: a client slowed by a loaded machine must not be taken for a lost one.
        [os.path.join(BIN, "s2sim-run"), SCENE, "--duration", str(DURATION_S),
         "--define", "remote_port=0", "--define", "remote_wait_s=120", "--log", str(sim_log),
         "--log-period", "0.04", "--signals", ROBOT + "x", ROBOT + "y", ROBOT + "yaw", "--quiet"])
    client = subprocess.Popen(
        [sys.executable, CLIENT, "--port", str(port), "--seed", "7", "--log", str(client_log)],
        stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    return runner, client, sim_log, client_log


def finish(tour):
    runner, client, sim_log, client_log = tour
    out, _ = client.communicate(timeout=300)
    assert runner.wait(timeout=300) == 0, runner.stderr.read()
    assert client.returncode == 0, out
    return out, sim_log, client_log


def test_the_arena_file_is_what_its_script_writes():
    script = os.path.join(SOURCE, "scripts", "make-firefighting-arena.py")
    written = subprocess.run([sys.executable, script], capture_output=True, text=True, check=True)
    assert written.stdout == open(os.path.join(SCENE, "arena.xml")).read()


def test_every_sensor_is_noisy():
    body = ET.parse(os.path.join(SCENE, "omni_ir.xml")).getroot()
    sensors = list(body.iter("IRSharp"))
    assert len(sensors) == 6
    for ir in sensors:
        noise = ir.find("noise")
        assert noise is not None and float(noise.get("var_k")) > 0 and float(noise.get("var_d")) > 0


def test_the_tour_reaches_every_room_localised_within_5_cm_and_repeats(tmp_path, capsys):
    # The two runs side by side: each waits on its own client, their results must not differ.
    tours = [start_tour(tmp_path, "a"), start_tour(tmp_path, "b")]
    (out, sim_log, client_log), (_, sim_b, client_b) = [finish(t) for t in tours]

    assert filecmp.cmp(sim_log, sim_b, shallow=False), "simulation logs differ"
    assert filecmp.cmp(client_log, client_b, shallow=False), "client logs differ"

    truth = np.genfromtxt(sim_log, delimiter=",", skip_header=1)  # time, x, y, yaw
    client = np.genfromtxt(client_log, delimiter=",", names=True)
    at = {round(row[0], 6): row[1:] for row in truth}
    tour = client[client["touring"] == 1]
    true = np.array([at[round(t, 6)] for t in tour["time"]])  # the simulation's pose, same tick
    error = np.hypot(tour["est_x"] - true[:, 0], tour["est_y"] - true[:, 1])
    odometry = np.hypot(tour["odo_x"] - true[:, 0], tour["odo_y"] - true[:, 1])
    yaw = np.angle(np.exp(1j * (tour["est_yaw"] - true[:, 2])))
    rms_m, odometry_rms_m = np.sqrt(np.mean(error ** 2)), np.sqrt(np.mean(odometry ** 2))
    yaw_rms_deg = np.degrees(np.sqrt(np.mean(yaw ** 2)))

    # Every room entered, by the true pose: past the door's wall by DEPTH_M.
    arrivals = {}
    rooms = room_insides()
    assert len(rooms) == 4
    for name, (x0, y0, x1, y1) in rooms.items():
        inside = ((truth[:, 1] > x0 + DEPTH_M) & (truth[:, 1] < x1 - DEPTH_M) &
                  (truth[:, 2] > y0 + DEPTH_M) & (truth[:, 2] < y1 - DEPTH_M))
        arrivals[name] = truth[np.argmax(inside), 0] if inside.any() else None

    with capsys.disabled():
        print("\n" + out.strip())
        for name in sorted(arrivals, key=lambda n: arrivals[n] if arrivals[n] is not None else 1e9):
            print("%s: entered at t = %s s (true pose)" % (
                name, "never" if arrivals[name] is None else "%.2f" % arrivals[name]))
        print("over %.1f s of tour: estimate %.4f m RMS (largest %.4f m), yaw %.3f deg RMS; "
              "odometry alone %.4f m RMS" % (tour["time"][-1], rms_m, error.max(), yaw_rms_deg,
                                            odometry_rms_m))

    assert all(t is not None for t in arrivals.values()), arrivals
    assert out.count("reached at") == 4 and "tour done: 4 of 4 rooms" in out
    assert rms_m < 0.05
    assert rms_m < odometry_rms_m  # the IR ranges correct the odometry's drift
    assert len(tour) > 500
