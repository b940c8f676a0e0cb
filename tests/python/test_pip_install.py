"""`pip install --no-build-isolation .` (pyproject.toml, setup.py) into a fresh venv with the
system's site packages, offline: the wheel builds with CMake (here in the build tree CTest
uses, so that it only stages what is built), installs the module, the library and the plugins,
and the installed package loads a scene from another folder."""

import os
import subprocess
import sys

SOURCE = os.environ.get("S2SIM_SOURCE_DIR", os.getcwd())
BUILD = os.environ.get("S2SIM_BINARY_DIR", os.path.join(SOURCE, "build"))


def test_pip_installs_into_a_fresh_venv_offline(tmp_path):
    venv = tmp_path / "venv"
    subprocess.run([sys.executable, "-m", "venv", "--system-site-packages", "--without-pip",
                    str(venv)], check=True)
    python = str(venv / "bin" / "python")
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "S2SIM_PLUGIN_PATH")}
    env.update(S2SIM_CMAKE_BUILD_DIR=BUILD, PIP_NO_INDEX="1", PIP_DISABLE_PIP_VERSION_CHECK="1",
               PIP_NO_CACHE_DIR="1")
    # The system's pip, running in the venv, installs into the venv.
    out = subprocess.run([python, "-m", "pip", "install", "--no-build-isolation", "--no-deps",
                          SOURCE], env=env, capture_output=True, text=True, timeout=900)
    assert out.returncode == 0, out.stdout[-3000:] + out.stderr[-3000:]
    code = ("import s2sim, sys, importlib.metadata as m; "
            "assert s2sim.__file__.startswith(sys.argv[1]), s2sim.__file__; "
            "s = s2sim.Simulation(sys.argv[2]); s.step(20); "
            "from s2sim.envs import CartPoleEnv; CartPoleEnv().reset(seed=1); "
            "eps = [e.value for e in m.entry_points(group='gymnasium.envs')]; "
            "print(s.time, m.version('s2sim'), eps)")
    run = subprocess.run([python, "-c", code, str(venv), os.path.join(SOURCE, "scenes", "nxt")],
                         cwd=str(tmp_path), env=env, capture_output=True, text=True, timeout=120)
    assert run.returncode == 0, run.stderr
    time_s, version, entry_points = run.stdout.split(" ", 2)
    assert float(time_s) == 0.02
    assert version == s2sim_version()
    assert "s2sim.envs:register_envs" in entry_points
    assert (venv / "lib" / "s2sim" / "plugins" / "liblinks.so").exists()


def s2sim_version():
    import s2sim
    return s2sim.sdk_version
