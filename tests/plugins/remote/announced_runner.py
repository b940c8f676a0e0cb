"""s2sim-run on a scene whose remote link the system gives a port (--define remote_port=0): the
runner started, and the port it announces on stderr."""

import re
import subprocess


def start_announced_runner(command):
    """Starts `command` (an s2sim-run command line) with stderr piped; returns (process, port)
    once the link's announce line, after any warning, says the port."""
    runner = subprocess.Popen(command, stderr=subprocess.PIPE, text=True)
    port, line = None, ""
    for _ in range(100):
        line = runner.stderr.readline()
        port = re.search(r"udp 127\.0\.0\.1:(\d+)", line)
        if port or not line:
            break
    assert port, line
    return runner, int(port.group(1))
