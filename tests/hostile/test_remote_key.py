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
