"""The examples of python/examples run as a user runs them (the remote examples are run
against the runner by tests/plugins/remote/: the cart-pole by test_remote.py, the omni tour by
test_omni_tour.py)."""

import csv
import os
import subprocess
import sys

SOURCE = os.environ.get("S2SIM_SOURCE_DIR", os.getcwd())
EXAMPLES = os.path.join(SOURCE, "python", "examples")


def run(name, *args):
    env = {k: v for k, v in os.environ.items() if k != "DISPLAY"}  # cameras draw headless
    out = subprocess.run([sys.executable, os.path.join(EXAMPLES, name), *args],
                         capture_output=True, text=True, timeout=240, env=env)
    assert out.returncode == 0, out.stdout + out.stderr
    return out.stdout


def test_python_pid_drives_the_nxt_to_its_target():
    line = run("nxt_pid.py", "--target", "0.5")
    x = float(line.split("x = ")[1].split()[0])
    assert abs(x - 0.5) < 0.01


def test_gymnasium_style_environment():
    sys.path.insert(0, EXAMPLES)
    try:
        import cartpole_env
    finally:
        sys.path.pop(0)
    env = cartpole_env.CartPoleEnv()
    obs, info = env.reset(seed=3)
    assert obs.shape == (4,) and env.observation_space.contains(obs)
    first = [env.step([1.0])[0] for _ in range(10)]
    obs2, info2 = env.reset(seed=3)  # same seed, same episode
    assert (obs2 == obs).all() and info2 == info
    assert all((a == env.step([1.0])[0]).all() for a in first)
    obs, reward, terminated, truncated, _ = env.step(env.action_space.sample())
    assert reward in (0.0, 1.0) and isinstance(terminated, bool) and isinstance(truncated, bool)
    assert "linear policy returns: [500.0" in run("cartpole_env.py")


def test_camera_seeker_drives_to_the_post_on_its_image_alone():
    # The controller sees only the camera's image; the robot's pose is read here, in the test.
    os.environ.pop("DISPLAY", None)  # the camera draws headless
    sys.path.insert(0, EXAMPLES)
    try:
        import seek_target
    finally:
        sys.path.pop(0)
    for target in ((1.2, 0.5), (-0.4, -0.8)):  # ahead on the left; behind on the right
        sim, done = seek_target.seek(target, duration_s=15.0)
        assert done, target
        x, y = sim.signal("robots/seeker/x"), sim.signal("robots/seeker/y")
        distance = ((target[0] - x) ** 2 + (target[1] - y) ** 2) ** 0.5
        assert 0.2 < distance < 0.4, (target, distance)  # near the post, short of touching it
        assert abs(sim.signal("robots/seeker/vx")) < 0.01  # stopped
    assert "reached the post" in run("seek_target.py", "--target", "0.9", "-0.3")


def test_monte_carlo_stopping_sweep_writes_a_table_and_a_png(tmp_path):
    run("nxt_stopping_sweep.py", "--samples", "8", "--workers", "2", "--out", str(tmp_path))
    with open(tmp_path / "stopping.csv") as f:
        rows = list(csv.DictReader(f))
    assert len(rows) == 8 and len({r["seed"] for r in rows}) == 8
    assert all(0 < float(r["stopping_distance_m"]) < 0.05 for r in rows)
    assert len({r["stopping_distance_m"] for r in rows}) == 8  # the parameters matter
    with open(tmp_path / "stopping.png", "rb") as f:
        assert f.read(8) == b"\x89PNG\r\n\x1a\n"


def test_humanoid_walk_from_python_as_a_user_runs_it():
    # The full minute, against the script's walk, is tests/plugins/servo/test_humanoid_walk.py.
    line = run("humanoid_walk.py", "--duration", "10")
    distance = float(line.split("distance ")[1].split()[0])
    lowest = float(line.split("lowest trunk height ")[1].split()[0])
    assert distance > 0.2 and lowest > 70, line
