"""The SimTwo paper's humanoid (scenes/humanoid, section 4.2): with its script (control.pas) in
s2sim-run, at 1 ms without substeps, it walks at least 2 m along x in 60 s, straight, the trunk
never below 70 % of its standing height; two runs write identical logs; the same key poses
driven from Python (python/examples/humanoid_walk.py) give the same walk, bit for bit
(docs/tutorials/humanoid-walk.md)."""

import csv
import filecmp
import json
import math
import os
import subprocess
import sys

SOURCE = os.environ.get("S2SIM_SOURCE_DIR", os.getcwd())
BIN = os.environ.get("S2SIM_BIN_DIR", os.path.join(SOURCE, "build", "bin"))
SCENE = os.path.join(SOURCE, "scenes", "humanoid")
DURATION_S = 60
TRUNK = "robots/humanoid/solids/trunk/"

sys.path.insert(0, os.path.join(SOURCE, "python", "examples"))
import humanoid_walk  # noqa: E402


def run_script(log):
    """The walk from s2sim-run: the trunk's log, and its final x at full precision."""
    summary = log.with_suffix(".json")
    subprocess.run([os.path.join(BIN, "s2sim-run"), SCENE, "--duration", str(DURATION_S),
                    "--log", str(log), "--summary", str(summary), "--no-timing",
                    "--signals", TRUNK + "x", TRUNK + "y", TRUNK + "z", TRUNK + "yaw"],
                   check=True, capture_output=True, text=True)
    with open(log) as f:
        rows = list(csv.reader(f))
    names = [n.split(" ")[0] for n in rows[0]]
    with open(summary) as f:
        final_x = json.load(f)["robots"][0]["x"]  # the main body: the trunk
    return {n: [float(r[i]) for r in rows[1:]] for i, n in enumerate(names)}, final_x


def test_walks_two_metres_in_a_minute_without_falling_and_repeats(tmp_path):
    first, second = tmp_path / "walk_1.csv", tmp_path / "walk_2.csv"
    log, final_x = run_script(first)
    run_script(second)
    assert filecmp.cmp(first, second, shallow=False), "two runs wrote different logs"
    assert filecmp.cmp(first.with_suffix(".json"), second.with_suffix(".json"), shallow=False)

    x, y, z, yaw = (log[TRUNK + k] for k in ("x", "y", "z", "yaw"))
    assert log["time"][-1] == DURATION_S
    standing = z[0]  # at load: the legs straight
    distance, lowest = x[-1] - x[0], min(z) / standing
    drift = max(abs(v - y[0]) for v in y)
    print(f"script: {distance:.4f} m in {DURATION_S} s, lowest trunk {100 * lowest:.1f} % of "
          f"standing ({standing:.4f} m), lateral drift {drift:.4f} m, final yaw {yaw[-1]:.4f} rad")
    assert distance >= 2.0
    assert lowest > 0.7
    assert drift < 0.25 and abs(yaw[-1]) < 0.2  # straight ahead

    # The same key poses from Python: the trunk's path is the script's, tick by tick (to the
    # log's ten digits), and it ends at the same double.
    path = []
    py_distance, py_lowest = humanoid_walk.walk(
        DURATION_S, on_tick=lambda sim: path.append((sim.signal(TRUNK + "x"),
                                                     sim.signal(TRUNK + "z"))))
    print(f"python: {py_distance:.4f} m, lowest trunk {100 * py_lowest:.1f} %, final x "
          f"{path[-1][0]!r} (script {final_x!r})")
    assert len(path) == len(x) - 1
    for (px, pz), sx, sz in zip(path, x[1:], z[1:]):
        assert math.isclose(px, sx, rel_tol=1e-9, abs_tol=1e-12)
        assert math.isclose(pz, sz, rel_tol=1e-9, abs_tol=1e-12)
    assert path[-1][0] == final_x
    assert abs(py_distance - distance) < 1e-9 and abs(py_lowest - lowest) < 1e-9


def test_an_elbow_step_follows_the_servos_speed_limit_and_settles(tmp_path):
    """The plot of scripts/plot-humanoid-servo.sh (the paper's Figure 20): standing without
    its script, the right elbow's goal steps from 0 to 60°; the angle follows the setpoint
    that moves at the AX-12's 6.18 rad/s, never faster, and settles within 1° without ringing
    (the forearm alone, 5e-5 kg·m², is light for 1 ms: the servo's torque is an implicit drive
    and its gear adds the rotor's reflected inertia)."""
    axis = "robots/humanoid/axes/elbow_r/"
    log = tmp_path / "step.csv"
    goal = math.radians(60)
    subprocess.run([os.path.join(BIN, "s2sim-run"), SCENE, "--duration", "0.5", "--no-script",
                    "--set", f"{axis}ref_pos={goal!r}", "--log", str(log),
                    "--signals", axis + "pos", axis + "speed"],
                   check=True, capture_output=True, text=True)
    with open(log) as f:
        rows = [[float(v) for v in r] for r in list(csv.reader(f))[1:]]
    inside = [t for t, pos, _ in rows if abs(pos - goal) < math.radians(1)]
    settled = next(t for t in inside if all(abs(p - goal) < math.radians(1)
                                            for tt, p, _ in rows if tt >= t))
    top_speed = max(abs(w) for _, _, w in rows)
    print(f"elbow: within 1 deg from {settled:.3f} s (the speed-limited move alone "
          f"{goal / 6.18:.3f} s), top speed {top_speed:.3f} rad/s, final "
          f"{math.degrees(rows[-1][1]):.3f} deg")
    assert settled < goal / 6.18 + 0.1
    assert top_speed < 6.18 * 1.05
    assert abs(rows[-1][2]) < 1e-3
