#!/usr/bin/python3
"""Monte-Carlo sweep of the NXT's stopping distance over its motor parameters, on Dask, with a
PNG plot (gnuplot):

    PYTHONPATH=build/python /usr/bin/python3 python/examples/nxt_stopping_sweep.py \
        --samples 40 --workers 2 --out /tmp/stopping

Each run drives scenes/nxt straight at 6 V for 1 s, then sets the voltage to 0 (the H-bridge
shorts the motor: back-EMF braking) and measures how far it rolls until t = 3 s. The motor's
resistance, torque constant and viscous friction are drawn uniformly within +-15 % of Table 2
of the SimTwo paper (scene args motor_ri, motor_ki, friction_bv). Writes stopping.csv and
stopping.png in --out; every row holds the seed and parameters that repeat it.
"""

import argparse
import csv
import math
import os
import subprocess
import sys

import numpy as np

import s2sim

SCENE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scenes", "nxt")
RIGHT, LEFT = "robots/nxt/axes/right/ref_voltage", "robots/nxt/axes/left/ref_voltage"
NOMINAL = {"motor_ri": 7.6, "motor_ki": 0.4908, "friction_bv": 1.92e-3}


def stopping_distance(sim, params):
    sim.set_input(RIGHT, 6.0)
    sim.set_input(LEFT, -6.0)
    sim.run_until(1.0)
    x0, y0, speed = (sim.signal("robots/nxt/" + n) for n in ("x", "y", "vx"))
    sim.set_input(RIGHT, 0.0)
    sim.set_input(LEFT, 0.0)
    sim.run_until(3.0)
    x, y = sim.signal("robots/nxt/x"), sim.signal("robots/nxt/y")
    return {"speed_at_cut_m_s": speed, "stopping_distance_m": math.hypot(x - x0, y - y0),
            "final_speed_m_s": sim.signal("robots/nxt/vx")}


def samples(count, seed, spread=0.15):
    rng = np.random.default_rng(seed)
    return [{"seed": seed + i, **{k: float(v * rng.uniform(1 - spread, 1 + spread))
                                  for k, v in NOMINAL.items()}} for i in range(count)]


def plot(csv_path, png_path):
    script = """
set terminal pngcairo size 900,600
set output '%s'
set datafile separator ','
set key autotitle columnhead
set title 'NXT stopping distance from 6 V (Monte-Carlo over motor parameters, +-15 %%)'
set xlabel 'motor torque constant ki [N m/A]'
set ylabel 'stopping distance [mm]'
set cblabel 'armature resistance ri [ohm]'
set grid
plot '%s' using 3:($6*1000):2 with points pt 7 ps 1.5 palette notitle
""" % (png_path, csv_path)
    subprocess.run(["gnuplot"], input=script, text=True, check=True)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--samples", type=int, default=40)
    parser.add_argument("--workers", type=int, default=2)
    parser.add_argument("--seed", type=int, default=100)
    parser.add_argument("--scheduler", help="address of an existing Dask scheduler")
    parser.add_argument("--out", default=".")
    args = parser.parse_args()

    table = s2sim.sweep(SCENE, samples(args.samples, args.seed), run=stopping_distance,
                        workers=args.workers, scheduler=args.scheduler)
    rows = table.to_dict("records") if hasattr(table, "to_dict") else table
    os.makedirs(args.out, exist_ok=True)
    csv_path, png_path = os.path.join(args.out, "stopping.csv"), os.path.join(args.out, "stopping.png")
    columns = ["seed", "motor_ri", "motor_ki", "friction_bv", "speed_at_cut_m_s",
               "stopping_distance_m", "final_speed_m_s"]
    with open(csv_path, "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=columns)
        writer.writeheader()
        for row in rows:
            writer.writerow({k: row[k] for k in columns})
    plot(csv_path, png_path)
    d = np.array([r["stopping_distance_m"] for r in rows])
    print("%d runs: stopping distance %.2f mm +- %.2f mm (min %.2f, max %.2f); %s, %s"
          % (len(d), 1000 * d.mean(), 1000 * d.std(), 1000 * d.min(), 1000 * d.max(),
             csv_path, png_path))
    return 0


if __name__ == "__main__":
    sys.exit(main())
