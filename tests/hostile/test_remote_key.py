"""A remote link with a shared key (key_file) answers only datagrams signed with it: an unsigned
or wrongly signed datagram is dropped and counted in `unauthenticated`, never applied, never
answered. `allow_remote` without a key is refused at load: with no key anyone on the network
could drive the robot (before, `allow_remote='1'` had no authentication at all)."""

import os
import socket
import time

import pytest

import s2sim
from s2sim import remote

SOURCE = os.environ.get("S2SIM_SOURCE_DIR", os.getcwd())
REALTIME = os.path.join(SOURCE, "tests", "plugins", "remote", "fixtures", "realtime")
FORCE = "robots/cartpole/axes/slide/ref_torque"
LINK = "controllers/link/"
KEY = b"a shared key of thirty-two bytes"


def scene_with(tmp_path, attributes, key=KEY):
    """The real-time cart-pole fixture with `attributes` on its link, and a key file."""
    key_file = tmp_path / "link.key"
    key_file.write_bytes(key + b"\n")
    scene = open(os.path.join(REALTIME, "scene.xml")).read()
    scene = scene.replace("../../../../../scenes", os.path.join(SOURCE, "scenes"))
    scene = scene.replace("announce='0'", "announce='0' " + attributes.replace("KEY", str(key_file)))
    (tmp_path / "scene.xml").write_text(scene)
    return str(tmp_path), str(key_file)


def send_raw(port, datagram):
    s = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    s.sendto(datagram, ("127.0.0.1", port))
    return s


def test_allow_remote_without_a_key_is_refused_at_load(tmp_path):
    folder, _ = scene_with(tmp_path, "address='0.0.0.0' allow_remote='1'")
    with pytest.raises(s2sim.SceneError) as e:
        s2sim.Simulation(folder)
    assert e.value.attribute == "allow_remote" and "key_file" in e.value.message


def test_a_key_shorter_than_sixteen_bytes_is_a_located_error(tmp_path):
    folder, _ = scene_with(tmp_path, "key_file='KEY'", key=b"short")
    with pytest.raises(s2sim.SceneError) as e:
        s2sim.Simulation(folder)
    assert e.value.attribute == "key_file" and "at least 16" in e.value.message


def test_allow_remote_with_a_key_loads(tmp_path):
    folder, _ = scene_with(tmp_path, "address='0.0.0.0' allow_remote='1' key_file='KEY'")
    sim = s2sim.Simulation(folder)
    assert sim.signal(LINK + "port") > 0


def test_only_datagrams_signed_with_the_key_are_applied(tmp_path):
    folder, key_file = scene_with(tmp_path, "key_file='KEY'")
    sim = s2sim.Simulation(folder)
    port = int(sim.signal(LINK + "port"))
    key = remote.read_key(key_file)
    assert key == KEY
    with remote.Client(port=port, key=key) as link:
        link.send([1.0])
        sim.step(20)
        assert sim.input(FORCE) == 1.0
        t, y = link.receive(timeout=2.0)  # the link's replies are signed too
        assert len(y) == 2
        # Unsigned, signed with another key, and a good datagram with one byte changed.
        bad = [
            remote.pack(remote.INPUTS, 1000, remote.pack_doubles([99.0])),
            remote.pack(remote.INPUTS, 1001, remote.pack_doubles([99.0]), b"another key, 16+ bytes"),
        ]
        forged = bytearray(remote.pack(remote.INPUTS, 1002, remote.pack_doubles([99.0]), key))
        forged[20] ^= 1
        bad.append(bytes(forged))
        for datagram in bad:
            send_raw(port, datagram)
        time.sleep(0.01)
        sim.step(20)
        assert sim.input(FORCE) == 1.0, "an unauthenticated datagram was applied"
        assert sim.signal(LINK + "unauthenticated") == 3
        link.send([2.0])  # the client goes on
        sim.step(20)
        assert sim.input(FORCE) == 2.0


def test_a_client_without_the_key_gets_no_answer(tmp_path):
    folder, _ = scene_with(tmp_path, "key_file='KEY'")
    sim = s2sim.Simulation(folder)
    port = int(sim.signal(LINK + "port"))
    with remote.Client(port=port, timeout=0.3) as stranger:
        stranger.send([5.0])
        time.sleep(0.01)
        sim.step(40)
        with pytest.raises(remote.RemoteError, match="no reply"):
            stranger.receive(timeout=0.3)
    assert sim.input(FORCE) == 0.0
    assert sim.signal(LINK + "unauthenticated") >= 1
    assert sim.signal(LINK + "received") == 0


C_CLIENT = r'''
#include "s2sim_remote.h"
#include <stdio.h>
#include <stdlib.h>
/* "hmac KEYHEX DATAHEX": the tag; "talk PORT KEYFILE": three lock-step steps on a keyed link. */
static size_t unhex(const char* s, unsigned char* out) {
  size_t n = 0;
  for (; s[0] && s[1]; s += 2) {
    unsigned v;
    sscanf(s, "%2x", &v);
    out[n++] = (unsigned char)v;
  }
  return n;
}
int main(int argc, char** argv) {
  static unsigned char key[4096], data[4096], tag[32];
  if (argc == 4 && argv[1][0] == 'h') {
    size_t k = unhex(argv[2], key), d = unhex(argv[3], data), i;
    s2sim_remote_hmac(key, k, data, d, tag);
    for (i = 0; i < 32; ++i) printf("%02x", tag[i]);
    printf("\n");
    return 0;
  }
  if (argc == 4 && argv[1][0] == 't') {
    s2sim_remote_client c;
    double t = -1, y[8], u = 1.0;
    int i, n = 0;
    size_t size;
    FILE* f = fopen(argv[3], "rb");
    if (!f) return 2;
    size = fread(key, 1, sizeof key, f);
    fclose(f);
    if (size > 0 && key[size - 1] == '\n') --size;
    if (s2sim_remote_open(&c, "127.0.0.1", (uint16_t)atoi(argv[2])) != 0) return 2;
    if (s2sim_remote_set_key(&c, key, size) != 0) return 3;
    for (i = 0; i < 3; ++i) n = s2sim_remote_step(&c, &u, 1, &t, y, 8, 5000);
    u = 0;
    s2sim_remote_send(&c, S2SIM_REMOTE_INPUTS, &u, 1); /* lets the last period run */
    printf("%d %.6f\n", n, t);
    s2sim_remote_close(&c);
    return n == 4 ? 0 : 1;
  }
  return 2;
}
'''


@pytest.fixture
def c_client(tmp_path):
    import shutil
    import subprocess
    if shutil.which("cc") is None:
        pytest.skip("no C compiler")
    source = tmp_path / "client.c"
    source.write_text(C_CLIENT)
    exe = tmp_path / "client"
    subprocess.run(["cc", "-std=c99", "-Wall", "-Wextra", "-Werror", "-D_POSIX_C_SOURCE=200809L",
                    "-I", os.path.join(SOURCE, "plugins", "remote", "include"), str(source),
                    "-o", str(exe)], check=True)
    return str(exe)


def test_the_c_clients_tags_are_hmac_sha256(c_client):
    import hashlib
    import hmac
    import random
    import subprocess
    rng = random.Random(7)
    # Keys shorter and longer than a block, messages of 0 to 3 blocks and their edges.
    for key_size, data_size in [(16, 0), (32, 55), (64, 56), (65, 64), (200, 119), (20, 1000)]:
        key = bytes(rng.randrange(256) for _ in range(key_size))
        data = bytes(rng.randrange(256) for _ in range(data_size))
        out = subprocess.run([c_client, "hmac", key.hex() or "", data.hex() or "-"],
                             capture_output=True, text=True, check=True).stdout.strip()
        want = hmac.new(key, data if data_size else b"", hashlib.sha256).hexdigest()
        assert out == want, (key_size, data_size)


def test_the_c_client_steps_a_keyed_link(tmp_path, c_client):
    import subprocess
    import threading
    key_file = tmp_path / "link.key"
    key_file.write_bytes(KEY + b"\n")
    scene = open(os.path.join(SOURCE, "scenes", "cartpole_remote", "scene.xml")).read()
    scene = scene.replace("file='", "file='%s/" % os.path.join(SOURCE, "scenes", "cartpole_remote"))
    scene = scene.replace("mode='lockstep'", "mode='lockstep' key_file='%s'" % key_file)
    folder = tmp_path / "scene"
    folder.mkdir()
    (folder / "scene.xml").write_text(scene)
    sim = s2sim.Simulation(str(folder), defines={"remote_port": 0, "remote_wait_s": 5.0})
    port = int(sim.signal(LINK + "port"))
    runner = threading.Thread(target=sim.step, args=(4 * 20,))
    runner.start()
    out = subprocess.run([c_client, "talk", str(port), str(key_file)], capture_output=True,
                         text=True, timeout=30)
    runner.join(10)
    assert out.returncode == 0, out.stdout + out.stderr
    assert out.stdout.split()[0] == "4"
    assert sim.signal(LINK + "unauthenticated") == 0
