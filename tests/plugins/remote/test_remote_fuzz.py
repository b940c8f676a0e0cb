"""Fuzzing the remote port: at least 100 000 malformed datagrams (random, truncated, oversized,
wrong magic, version, length or type, non-finite inputs) sent at full rate while the simulation
steps. It keeps stepping, counts every datagram the system delivered (the socket's own drops,
from /proc/net/udp, make up the rest), and its state is the same as a run without them."""

import os
import random
import socket
import struct
import threading
import time

import numpy as np

import s2sim
from s2sim import remote

REALTIME = os.path.join(os.path.dirname(__file__), "fixtures", "realtime")
LINK = "controllers/link/"
COUNT = 100_000
PERIOD_TICKS = 20  # the fixture's control period, 20 ms at 1 ms


def bad_datagram(rng):
    """One datagram the link must drop (the fixture serves one input)."""
    kind = rng.randrange(10)
    valid = remote.pack(remote.INPUTS, rng.randrange(1, 1 << 32), struct.pack("<d", 1.0))
    if kind == 0:  # noise
        return rng.randbytes(rng.randrange(0, 200))
    if kind == 1:  # truncated: a valid request cut short
        return valid[:rng.randrange(0, len(valid))]
    if kind == 2:  # oversized: more doubles than inputs, the length field agreeing
        return remote.pack(remote.INPUTS, 7, rng.randbytes(8 * rng.randrange(2, 100)))
    if kind == 3:  # oversized: one in fifty is as large as a datagram gets
        size = remote.MAX_DATAGRAM if rng.randrange(50) == 0 else rng.randrange(17, 4000)
        return valid[:16] + rng.randbytes(size - 16)
    if kind == 4:  # bad magic
        return b"S2SX" + valid[4:]
    if kind == 5:  # another version
        return valid[:4] + struct.pack("<H", rng.choice([0, 2, 0xFFFF])) + valid[6:]
    if kind == 6:  # the length field disagrees with the size
        return valid[:12] + struct.pack("<I", rng.choice([0, 16, 9, 0xFFFFFFFF])) + valid[16:]
    if kind == 7:  # non-finite input
        bad = rng.choice([float("nan"), float("inf"), float("-inf")])
        return remote.pack(remote.INPUTS, 9, struct.pack("<d", bad))
    if kind == 8:  # unknown type
        return remote.pack(rng.choice([0, 2, 5, 6, 999]), 3, b"")
    return remote.pack(rng.choice([remote.HELLO, remote.OBSERVE]), 4, rng.randbytes(8))  # payload


def socket_drops(port):
    """The system's count of datagrams dropped at the socket (receive buffer full)."""
    with open("/proc/net/udp") as table:
        for line in list(table)[1:]:
            fields = line.split()
            if int(fields[1].split(":")[1], 16) == port:
                return int(fields[-1])
    raise AssertionError("port %d not in /proc/net/udp" % port)


def test_fuzzed_port_keeps_stepping_counts_and_leaves_the_state_alone():
    rng = random.Random(14)
    datagrams = [bad_datagram(rng) for _ in range(2000)]  # cycled: the sender stays fast
    sim = s2sim.Simulation(REALTIME)
    port = int(sim.signal(LINK + "port"))
    sent = [0]
    stop = threading.Event()

    def flood():  # until the link has counted COUNT: the socket may drop some on the way
        out = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
        while not stop.is_set():
            for datagram in datagrams:
                out.sendto(datagram, ("127.0.0.1", port))
            sent[0] += len(datagrams)
        out.close()

    sender = threading.Thread(target=flood)
    start = time.perf_counter()
    sender.start()
    periods_during = 0
    while sim.signal(LINK + "dropped") < COUNT:
        sim.step(PERIOD_TICKS)
        periods_during += 1
    stop.set()
    sender.join()
    flood_s = time.perf_counter() - start
    for _ in range(50):  # the datagrams still queued are read in the next periods
        sim.step(PERIOD_TICKS)
    ticks = sim.tick

    dropped = int(sim.signal(LINK + "dropped"))
    lost = socket_drops(port)
    print("\n%d datagrams in %.2f s (%.0f/s); %d periods stepped meanwhile; counted %d, "
          "dropped by the socket %d" % (sent[0], flood_s, sent[0] / flood_s, periods_during,
                                          dropped, lost))
    assert dropped >= COUNT
    assert periods_during > 10, "the simulation did not keep stepping"
    assert dropped + lost == sent[0], "a datagram was neither counted nor dropped by the socket"
    assert sim.signal(LINK + "received") == 0 and sim.signal(LINK + "link") == 0

    quiet = s2sim.Simulation(REALTIME)
    while quiet.tick < ticks:
        quiet.step(PERIOD_TICKS)
    assert quiet.tick == ticks
    names = sim.signal_names("robots/cartpole/*")
    assert len(names) > 20
    assert np.array_equal(sim.signals("robots/cartpole/*"), quiet.signals("robots/cartpole/*"))
    assert sim.signal("robots/cartpole/solids/pole/pitch") != 0.0  # it moved: a real comparison
