"""A SimTwo script against careless or hostile use: Halt, a kill while running, a UDP socket the
script never asked for, a raise located on its own line, a TextFile local. Each ran wrong on the
code before its fix (named in each test)."""

import os
import shutil
import signal
import socket
import subprocess
import time

import pytest

SOURCE = os.environ.get("S2SIM_SOURCE_DIR", os.getcwd())
RUNNER = os.path.join(os.environ.get("S2SIM_BIN_DIR", os.path.join(SOURCE, "build", "bin")),
                      "s2sim-run")
SCENE = os.path.join(SOURCE, "tests", "plugins", "pascal_script", "script_api")

pytestmark = pytest.mark.skipif(shutil.which("fpc") is None, reason="no fpc")


def free_udp_port():
    with socket.socket(socket.AF_INET, socket.SOCK_DGRAM) as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


@pytest.fixture
def run_script(tmp_path):
    """Writes `text` as a script and runs the test scene under it; returns the process, the
    CSV log's rows and the summary's path."""
    cache = tmp_path / "cache"
    temp = tmp_path / "tmp"
    temp.mkdir()

    def run(text, duration="1", wait=True, port=None):
        script = tmp_path / "control.pas"
        script.write_text(text)
        env = dict(os.environ, S2SIM_PASCAL_CACHE=str(cache), TMPDIR=str(temp),
                   S2SIM_UDP_PORT=str(port or free_udp_port()))
        env.pop("S2SIM_COM_PORT", None)
        args = [RUNNER, SCENE, "--script", str(script), "--duration", duration, "--quiet",
                "--no-timing", "--log", str(tmp_path / "log.csv"), "--summary",
                str(tmp_path / "summary.json")]
        for f in ("log.csv", "summary.json"):
            if (tmp_path / f).exists():
                (tmp_path / f).unlink()
        if not wait:
            return subprocess.Popen(args, env=env, stdout=subprocess.DEVNULL,
                                    stderr=subprocess.PIPE, text=True)
        done = subprocess.run(args, env=env, capture_output=True, text=True, timeout=300)
        rows = (tmp_path / "log.csv").read_text().splitlines()[1:] \
            if (tmp_path / "log.csv").exists() else []
        return done, rows, tmp_path / "summary.json"

    run.temp = temp
    return run


INITIALIZE = "procedure Initialize;\nbegin\nend;\n"

HALT = """var n: integer;
procedure Control;
begin
  n := n + 1;
  if n = 3 then begin
    try
      %s
    except
      on E: Exception do WriteLn('caught ' + E.Message);
    end;
  end;
end;
procedure Initialize;
begin
  n := 0;
end;
"""


def test_halt_ends_the_run_with_its_outputs_and_names_the_line(run_script):
    # Before: Halt ended s2sim-run with exit 0, no word, the CSV cut short and no summary.
    done, rows, summary = run_script(HALT % "Halt;")
    assert done.returncode == 0, done.stderr
    assert "the script called Halt(0) in Control" in done.stderr
    assert "control.pas:7" in done.stderr
    assert "caught" not in done.stdout + done.stderr  # an Exception handler lets it pass
    assert summary.exists()
    # The third call comes at step 120 (the script's period is 40 ms, its first call one step
    # early): the run ends there, its rows t = 0 and steps 1 to 120 written.
    assert len(rows) == 121


def test_halt_with_a_code_is_a_failed_run_not_a_plugin_error(run_script):
    # Before: Halt(3) gave exit 3, which means "plugin error".
    done, rows, summary = run_script(HALT % "Halt(3);")
    assert done.returncode == 5, done.stderr
    assert "the script called Halt(3) in Control" in done.stderr
    assert "non-zero Halt code" in done.stderr
    assert summary.exists() and len(rows) == 121


def test_a_killed_run_leaves_no_copy_of_the_script_behind(run_script):
    # Before: each crash, kill or Halt left a 2.3 MB /tmp/s2sim-script-* copy.
    stale = run_script.temp / "s2sim-script-old123"
    stale.write_bytes(b"left by a run killed before its load removed it")
    old = time.time() - 3600
    os.utime(stale, (old, old))
    fresh = run_script.temp / "s2sim-script-new456"  # another run's, being loaded right now
    fresh.write_bytes(b"x")
    mine = run_script.temp / "notes.txt"
    mine.write_text("not ours")
    proc = run_script(HALT % "n := 4;", duration="1000", wait=False)
    try:
        time.sleep(4)
        assert proc.poll() is None, proc.stderr.read()
        assert sorted(p.name for p in run_script.temp.iterdir()) == ["notes.txt",
                                                                   "s2sim-script-new456"]
    finally:
        proc.send_signal(signal.SIGKILL)
        proc.wait()
    assert sorted(p.name for p in run_script.temp.iterdir()) == ["notes.txt",
                                                               "s2sim-script-new456"]


def bound_udp_ports():
    """(address, port) of every UDP socket of this machine, from /proc/net/udp."""
    out = set()
    with open("/proc/net/udp") as f:
        for line in f.readlines()[1:]:
            local = line.split()[1]
            address, port = local.split(":")
            out.add((socket.inet_ntoa(bytes.fromhex(address)[::-1]), int(port, 16)))
    return out


def listens_on(port, proc):
    time.sleep(3)
    assert proc.poll() is None, proc.stderr.read()
    found = {a for a, p in bound_udp_ports() if p == port}
    proc.send_signal(signal.SIGKILL)
    proc.wait()
    return found


def test_a_script_without_udp_opens_no_socket(run_script):
    # Before: every scripted project bound UDP 0.0.0.0:9808, even with an empty control.pas.
    port = free_udp_port()
    proc = run_script("procedure Control;\nbegin\nend;\n" + INITIALIZE, duration="1000",
                      wait=False, port=port)
    assert listens_on(port, proc) == set()


def test_a_script_that_reads_udp_listens_on_loopback_only(run_script):
    port = free_udp_port()
    proc = run_script("procedure Control;\nvar s: string;\nbegin\n  s := ReadUDPData;\nend;\n" +
                      INITIALIZE, duration="1000", wait=False, port=port)
    assert listens_on(port, proc) == {"127.0.0.1"}


def test_the_scene_says_where_the_script_listens(tmp_path):
    # Before: only S2SIM_UDP_ADDRESS could move the script's socket off loopback, and a scene
    # could not say it.
    port = free_udp_port()
    scene = tmp_path / "scene"
    shutil.copytree(SCENE, scene)
    xml = (scene / "scene.xml").read_text()
    assert "<s2sim>" not in xml
    (scene / "scene.xml").write_text(xml.replace(
        "<scene>", "<scene>\n  <s2sim><udp address='127.0.0.2' port='%d'/></s2sim>" % port, 1))
    script = tmp_path / "control.pas"
    script.write_text("procedure Control;\nvar s: string;\nbegin\n  s := ReadUDPData;\nend;\n" +
                      INITIALIZE)
    env = dict(os.environ, S2SIM_PASCAL_CACHE=str(tmp_path / "cache"))
    for name in ("S2SIM_UDP_PORT", "S2SIM_UDP_ADDRESS", "S2SIM_COM_PORT"):
        env.pop(name, None)
    proc = subprocess.Popen([RUNNER, str(scene), "--script", str(script), "--duration", "1000",
                             "--quiet", "--no-timing"], env=env, stdout=subprocess.DEVNULL,
                            stderr=subprocess.PIPE, text=True)
    assert listens_on(port, proc) == {"127.0.0.2"}


def test_a_raise_is_located_on_its_own_line(run_script):
    # Before: a raise on line 8 was reported at line 4, the statement before it.
    text = ("var n: integer;\n"                               # 1
            "procedure Control;\n"                            # 2
            "begin\n"                                         # 3
            "  n := n + 1;\n"                                 # 4
            "  if n = 2 then\n"                               # 5
            "    WriteLn('second call');\n"                   # 6
            "  if n = 2 then\n"                               # 7
            "    raise Exception.Create('on purpose');\n"     # 8
            "end;\n" + INITIALIZE)
    done, rows, _ = run_script(text)
    assert done.returncode == 0, done.stderr
    assert "on purpose" in done.stderr
    assert "control.pas:8" in done.stderr, done.stderr


def test_a_local_text_file_compiles_and_writes(run_script, tmp_path):
    # Before: the locals' zero-fill wrote Default(TextFile), which fpc refuses.
    out = tmp_path / "written.txt"
    text = ("procedure Control;\n"
            "var f: TextFile;\n"
            "    k: integer;\n"
            "begin\n"
            "  AssignFile(f, '%s');\n"
            "  Rewrite(f);\n"
            "  System.WriteLn(f, 'k=', k);\n"
            "  CloseFile(f);\n"
            "end;\n" % out + INITIALIZE)
    done, _, _ = run_script(text, duration="0.1")
    assert done.returncode == 0, done.stderr
    assert out.read_text() == "k=0\n"  # and the integer beside it still starts at zero
