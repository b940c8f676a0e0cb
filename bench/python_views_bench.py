#!/usr/bin/python3
"""What the state views cost and save (docs/python.md, "State arrays").

    PYTHONPATH=build/python /usr/bin/python3 bench/python_views_bench.py

On scenes/nxt: reading the robot's signals as a copy (signals(glob)) against a gather from the
signal_values view; making a view; and what keeping the signal buffer up to date adds to the
calls that change the state (step(1), set_input: the buffer is rewritten once per call, not
per tick). Best of 9
repeats; prints JSON (microseconds).
"""

import json
import os
import timeit

import numpy as np

import s2sim

NXT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "scenes", "nxt")
RIGHT = "robots/nxt/axes/right/ref_voltage"


def best_us(call, number):
    return min(timeit.repeat(call, number=number, repeat=9)) / number * 1e6


def main():
    sim = s2sim.Simulation(NXT)
    names = sim.signal_names("robots/nxt/*")
    values = sim.signal_values
    rows = np.array([sim.signal_ids[n] for n in names])
    plain, kept = s2sim.Simulation(NXT), s2sim.Simulation(NXT)
    kept.signal_values  # from now on kept's buffer is rewritten by every change
    for s in (plain, kept):
        s.set_input(RIGHT, 6.0)
        s.step(100)
    out = {
        "signals": len(values),
        "values_read": len(names),
        "signals_glob_copy_us": best_us(lambda: sim.signals("robots/nxt/*"), 2000),
        "view_gather_us": best_us(lambda: values[rows], 2000),
        "make_q_view_us": best_us(lambda: sim.q, 2000),
        "step1_us": {"plain": best_us(lambda: plain.step(1), 500),
                     "buffer_kept": best_us(lambda: kept.step(1), 500)},
        "set_input_us": {"plain": best_us(lambda: plain.set_input(RIGHT, 6.0), 2000),
                         "buffer_kept": best_us(lambda: kept.set_input(RIGHT, 6.0), 2000)},
    }
    print(json.dumps(out, indent=1))


if __name__ == "__main__":
    main()
