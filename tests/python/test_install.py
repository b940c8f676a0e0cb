"""cmake --install puts a working package in <prefix>/lib/python3/dist-packages, which finds
the installed plugins (<prefix>/lib/s2sim/plugins) on its own."""

import os
import subprocess
import sys

SOURCE = os.environ.get("S2SIM_SOURCE_DIR", os.getcwd())
BUILD = os.environ.get("S2SIM_BINARY_DIR", os.path.join(SOURCE, "build"))


def test_installed_package_loads_scenes_with_the_installed_plugins(tmp_path):
    prefix = tmp_path / "prefix"
    subprocess.run([os.environ.get("CMAKE_COMMAND", "cmake"), "--install", BUILD, "--prefix",
                    str(prefix)], check=True, capture_output=True)
    package = prefix / "lib" / "python3" / "dist-packages"
    assert (package / "s2sim" / "remote.py").exists()
    assert (prefix / "lib" / "s2sim" / "plugins" / "liblinks.so").exists()
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "S2SIM_PLUGIN_PATH")}
    env["PYTHONPATH"] = str(package)
    code = ("import s2sim, sys; "
            "assert s2sim.__file__.startswith(sys.argv[1]), s2sim.__file__; "
            "s = s2sim.Simulation(sys.argv[2]); s.step(20); print(s.time)")
    out = subprocess.run([sys.executable, "-c", code, str(package),
                          os.path.join(SOURCE, "scenes", "nxt")],
                         cwd=str(tmp_path), env=env, capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    assert float(out.stdout) == 0.02
