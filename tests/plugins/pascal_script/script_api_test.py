#!/usr/bin/env python3
"""Every routine of SimTwo's list, called once by a script generated from it, in this folder's
script_api scene: each does what plugins/pascal_script/routines.tsv says (ok, or the named
error for rendering and what is not yet available). CloseSimTwo, among them, ends the run at
the step of the first script call (40 ms), exit 0, the summary written.

  script_api_test.py BIN_DIR PASCAL_CACHE        exit 77 (skip) without the list or fpc
"""
import os
import shutil
import socket
import json
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(os.path.dirname(HERE)))
GENERATOR = os.path.join(ROOT, "scripts", "script-api.py")


def free_udp_port():
    with socket.socket(socket.AF_INET, socket.SOCK_DGRAM) as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def main(bin_dir, cache):
    if shutil.which(os.environ.get("S2SIM_FPC", "fpc")) is None:
        print("skipped: no fpc", file=sys.stderr)
        return 77
    work = tempfile.mkdtemp(prefix="s2sim-script-api-")
    try:
        script = os.path.join(work, "all_routines.pas")
        with open(os.path.join(work, "thing.obj"), "w") as mesh:  # MeshThing's, beside the script
            mesh.write("v 0 0 0\nv 0.1 0 0\nv 0 0.1 0\nv 0 0 0.1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n")
        made = subprocess.run([sys.executable, GENERATOR, "script", script])
        if made.returncode != 0:
            return made.returncode  # 77: the list is absent
        env = dict(os.environ, S2SIM_SCRIPT_API_DIR=work, S2SIM_PASCAL_CACHE=cache,
                   S2SIM_UDP_PORT=str(free_udp_port()))
        env.pop("S2SIM_COM_PORT", None)
        stderr_path = os.path.join(work, "stderr.txt")
        summary_path = os.path.join(work, "summary.json")
        with open(stderr_path, "w") as err:
            run = subprocess.run([os.path.join(bin_dir, "s2sim-run"), os.path.join(HERE, "script_api"),
                                  "--script", script, "--duration", "0.2", "--summary",
                                  summary_path, "--no-timing"],
                                 env=env, stdout=subprocess.DEVNULL, stderr=err, timeout=600)
        if run.returncode != 0:
            print(open(stderr_path).read(), file=sys.stderr)
            print(f"s2sim-run exited {run.returncode}", file=sys.stderr)
            return 1
        with open(summary_path) as f:
            steps = json.load(f)["steps"]
        if steps != 40:
            print(f"CloseSimTwo: the run made {steps} steps, expected 40 (the first call's)",
                  file=sys.stderr)
            return 1
        return subprocess.run([sys.executable, GENERATOR, "expect", stderr_path]).returncode
    finally:
        shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1], sys.argv[2]))
