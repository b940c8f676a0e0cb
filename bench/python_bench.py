#!/usr/bin/python3
"""Overhead of the Python bindings and of the remote link (docs/benchmarks.md).

    PYTHONPATH=build/python /usr/bin/python3 bench/python_bench.py [--ticks 20000] [--periods 2000]

1. Bindings: Simulation.step(1) called `ticks` times against one step(ticks) call, on
   scenes/cartpole (two bodies: the stepping is cheap, so the per-call cost shows). The C++
   reference is build/bin/s2sim-facade-step-bench, run on the same scene when present.
2. Remote lock-step round trip: scenes/cartpole_remote stepped in a thread of this process,
   the pure-Python client in the main thread, one INPUTS request and its SIGNALS reply per
   20 ms control period, against stepping the same periods with no link. Loopback UDP.
   OBSERVE requests time the protocol's round trip alone (answered without stepping).
3. Threads: two Simulations of scenes/nxt stepped `ticks` ticks each, one after the other
   against on two Python threads at once (stepping releases the GIL): the speed-up, at most
   2 on two free cores.
Best of 9 repeats each (the least disturbed by the rest of the machine); prints JSON.
"""

import argparse
import json
import os
import subprocess
import threading
import time

import s2sim
from s2sim import remote

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
CARTPOLE = os.path.join(ROOT, "scenes", "cartpole")
CARTPOLE_REMOTE = os.path.join(ROOT, "scenes", "cartpole_remote")


def best(fn, repeats=9):
    return min(fn() for _ in range(repeats))


def bindings(ticks):
    sim = s2sim.Simulation(CARTPOLE)

    def one_by_one():
        sim.reset()
        t = time.perf_counter()
        for _ in range(ticks):
            sim.step(1)
        return time.perf_counter() - t

    def at_once():
        sim.reset()
        t = time.perf_counter()
        sim.step(ticks)
        return time.perf_counter() - t

    def with_read():
        sim.reset()
        t = time.perf_counter()
        for _ in range(ticks):
            sim.set_input("robots/cartpole/axes/slide/ref_torque", 0.0)
            sim.step(1)
            sim.signals("robots/cartpole/axes/*/pos")
        return time.perf_counter() - t

    def empty_calls():  # step(0): the call alone, GIL release included
        t = time.perf_counter()
        for _ in range(ticks):
            sim.step(0)
        return time.perf_counter() - t

    out = {"ticks": ticks,
           "py_us_per_step0_call": 1e6 * best(empty_calls) / ticks,
           "py_us_per_step1_call": 1e6 * best(one_by_one) / ticks,
           "py_us_per_tick_in_one_call": 1e6 * best(at_once) / ticks,
           "py_us_per_set_step1_signals": 1e6 * best(with_read) / ticks}
    exe = os.path.join(ROOT, "build", "bin", "s2sim-facade-step-bench")
    if os.path.exists(exe):
        out["cpp"] = json.loads(subprocess.run([exe, CARTPOLE, str(ticks)], capture_output=True,
                                               text=True, check=True).stdout)
    return out


def remote_round_trip(periods):
    sim = s2sim.Simulation(CARTPOLE_REMOTE, defines={"remote_port": 0})
    period_ticks = int(round(sim.control_period / sim.tick_s))
    port = int(sim.signal("controllers/link/port"))

    def linked():
        sim.reset()
        runner = threading.Thread(target=sim.step, args=(periods * period_ticks,))
        runner.start()
        with remote.Client(port=port) as link:
            link.hello()
            link.observe()
            t = time.perf_counter()
            for _ in range(periods - 1):
                link.step([0.0])
            elapsed = time.perf_counter() - t
            link.send([0.0])
        runner.join()
        return elapsed / (periods - 1)

    plain = s2sim.Simulation(CARTPOLE)

    def unlinked():
        plain.reset()
        t = time.perf_counter()
        for _ in range(periods):
            plain.set_input("robots/cartpole/axes/slide/ref_torque", 0.0)
            plain.step(period_ticks)
            plain.signals("robots/cartpole/axes/slide/*")
        return (time.perf_counter() - t) / periods

    def observe_round_trips():  # the protocol alone: OBSERVE is answered without stepping
        sim.reset()
        runner = threading.Thread(target=sim.step, args=(period_ticks,))
        runner.start()
        with remote.Client(port=port) as link:
            link.hello()
            t = time.perf_counter()
            for _ in range(periods):
                link.observe()
            elapsed = time.perf_counter() - t
            link.send([0.0])
        runner.join()
        return elapsed / periods

    with_link, without = best(linked), best(unlinked)
    return {"periods": periods, "period_ticks": period_ticks,
            "us_observe_round_trip": 1e6 * best(observe_round_trips),
            "us_per_period_lockstep": 1e6 * with_link,
            "us_per_period_bindings_no_link": 1e6 * without}


NXT = os.path.join(ROOT, "scenes", "nxt")


def separate_threads(ticks):
    sims = [s2sim.Simulation(NXT) for _ in range(2)]

    def one_after_the_other():
        for sim in sims:
            sim.reset()
        t = time.perf_counter()
        for sim in sims:
            sim.step(ticks)
        return time.perf_counter() - t

    def at_once():
        for sim in sims:
            sim.reset()
        threads = [threading.Thread(target=sim.step, args=(ticks,)) for sim in sims]
        t = time.perf_counter()
        for thread in threads:
            thread.start()
        for thread in threads:
            thread.join()
        return time.perf_counter() - t

    serial, parallel = best(one_after_the_other, 5), best(at_once, 5)
    return {"ticks_each": ticks, "s_one_after_the_other": serial, "s_on_two_threads": parallel,
            "speed_up": serial / parallel}


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--ticks", type=int, default=20000)
    parser.add_argument("--periods", type=int, default=2000)
    args = parser.parse_args()
    print(json.dumps({"bindings": bindings(args.ticks),
                      "remote_lockstep": remote_round_trip(args.periods),
                      "separate_threads": separate_threads(5 * args.ticks)}, indent=2))


if __name__ == "__main__":
    main()
