"""A remote link's session belongs to the address and port that opened it: another sender's
datagrams are answered BUSY, counted in `foreign` and never applied; sequence numbers are per
session; a silent client frees the session for the next one."""

import os
import socket
import threading
import time

import pytest

import s2sim
from s2sim import remote

SOURCE = os.environ.get("S2SIM_SOURCE_DIR", os.getcwd())
CARTPOLE = os.path.join(SOURCE, "scenes", "cartpole_remote")
REALTIME = os.path.join(SOURCE, "tests", "plugins", "remote", "fixtures", "realtime")
FORCE = "robots/cartpole/axes/slide/ref_torque"
LINK = "controllers/link/"


class Stranger:
    """A socket of its own (another port than the client's) that sends one datagram."""

    def __init__(self, port):
        self.socket = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
        self.address = ("127.0.0.1", port)

    def send(self, msg_type, sequence, payload=b""):
        self.socket.sendto(remote.pack(msg_type, sequence, payload), self.address)

    def reply(self, timeout=1.0):
        """The reply, if any within `timeout`, as (type, sequence, payload)."""
        self.socket.settimeout(timeout)
        try:
            return remote.unpack(self.socket.recv(remote.MAX_DATAGRAM + 1))
        except socket.timeout:
            return None


def test_a_spoofed_inputs_datagram_is_refused_and_does_not_lock_the_client_out():
    # Before: one INPUTS with sequence 0xFFFFFFFF from any local socket was applied, and the
    # real client's every request was stale from then on.
    sim = s2sim.Simulation(REALTIME)
    port = int(sim.signal(LINK + "port"))
    with remote.Client(port=port) as link:
        link.send([1.0])  # real time: the sender of the first INPUTS opens the session
        sim.step(20)
        assert sim.input(FORCE) == 1.0
        stranger = Stranger(port)
        stranger.send(remote.INPUTS, 0xFFFFFFFF, remote.pack_doubles([99.0]))
        time.sleep(0.01)  # arrived before the link's next period reads the socket
        sim.step(20)
        assert sim.input(FORCE) == 1.0, "a stranger's inputs were applied"
        reply = stranger.reply()
        assert reply is not None and reply[0] == remote.BUSY and reply[1] == 0xFFFFFFFF
        assert b"busy" in reply[2]
        link.send([2.0])  # the client's own sequence goes on
        sim.step(20)
        assert sim.input(FORCE) == 2.0
    assert sim.signal(LINK + "foreign") == 1
    assert sim.signal(LINK + "stale") == 0


def test_a_second_lockstep_client_is_told_busy_instead_of_answered_and_ignored():
    sim = s2sim.Simulation(CARTPOLE, defines={"remote_port": 0, "remote_wait_s": 5.0})
    port = int(sim.signal(LINK + "port"))
    period_ticks = int(round(sim.control_period / sim.tick_s))
    runner = threading.Thread(target=sim.step, args=(3 * period_ticks,))
    runner.start()
    with remote.Client(port=port) as first, remote.Client(port=port, timeout=2.0) as second:
        first.hello()
        t1, _ = first.step([0.5])
        with pytest.raises(remote.RemoteError, match="busy"):
            second.hello()
        with pytest.raises(remote.RemoteError, match="busy"):
            second.step([9.0])
        t2, _ = first.step([0.5])
        assert t2 == pytest.approx(t1 + 0.02)
        first.send([0.0])
    runner.join(10)
    assert not runner.is_alive()
    assert sim.signal(LINK + "foreign") == 2


def test_a_silent_client_frees_the_session_and_the_next_starts_its_own_sequence():
    sim = s2sim.Simulation(REALTIME, defines={"timeout_s": 0.2})
    port = int(sim.signal(LINK + "port"))
    with remote.Client(port=port) as first:
        first.sequence = 1000
        first.send([3.0])
        sim.step(20)
        assert sim.input(FORCE) == 3.0
        time.sleep(0.3)  # silent longer than the timeout: the link is lost, the session free
        sim.step(20)
        assert sim.input(FORCE) == 0.0
        with remote.Client(port=port) as second:  # sequence 1: not stale against 1000
            second.send([4.0])
            sim.step(20)
            assert sim.input(FORCE) == 4.0
            first.send([5.0])  # the first is now the stranger
            sim.step(20)
            assert sim.input(FORCE) == 4.0
    assert sim.signal(LINK + "stale") == 0 and sim.signal(LINK + "foreign") == 1


def test_a_client_that_closes_hands_the_session_on_at_once():
    sim = s2sim.Simulation(CARTPOLE, defines={"remote_port": 0, "remote_wait_s": 5.0})
    port = int(sim.signal(LINK + "port"))
    period_ticks = int(round(sim.control_period / sim.tick_s))
    runner = threading.Thread(target=sim.step, args=(3 * period_ticks,))
    runner.start()
    with remote.Client(port=port) as first:
        first.hello()
        first.step([0.5])
    # first said BYE when closed: the next client is served, not told busy for 5 s
    with remote.Client(port=port, timeout=2.0) as second:
        second.hello()
        second.step([0.5])
        second.send([0.0])
    runner.join(10)
    assert not runner.is_alive()
    assert sim.signal(LINK + "foreign") == 0
