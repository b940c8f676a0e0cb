#!/usr/bin/env python3
"""The humanoid of scenes/humanoid walks with its key-pose gait driven from Python: the library
does not run the scene's script (control.pas), and this loop sets the 19 servos' goals at the
script's ticks (every control period, from one period less a physics step: docs/scripting.md,
"Timing"), with the same table (humanoid_gait.py) and the same arithmetic, so the walk is the
script's, bit for bit.

    PYTHONPATH=build/python python3 python/examples/humanoid_walk.py [--duration 60] [--log FILE]

Prints the distance walked along x and the lowest trunk height relative to standing."""
import argparse
import os
import sys

import s2sim

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from humanoid_gait import AXES, DURATIONS, LOOP_START, POSES  # noqa: E402

DEG_TO_RAD = 0.017453292519943295
SCENE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scenes", "humanoid")


class KeyPoseGait:
    """The key poses interpolated per servo along a smoothstep, as control.pas does."""

    def __init__(self):
        self.pose, self.ticks = 0, 0

    def goals(self):
        """The next script tick's goals (rad), in AXES order."""
        self.ticks += 1
        if self.ticks > DURATIONS[self.pose]:
            self.ticks = 1
            self.pose += 1
            if self.pose >= len(POSES):
                self.pose = LOOP_START
        to = POSES[self.pose]
        start = POSES[self.pose - 1 if self.pose > 0 else 0]
        u = self.ticks / DURATIONS[self.pose]
        s = u * u * (3 - 2 * u)
        return [(a + (b - a) * s) * DEG_TO_RAD for a, b in zip(start, to)]


def walk(duration_s=60.0, scene=SCENE, defines=None, on_tick=None):
    """Runs the walk; returns (distance along x in m, lowest trunk height / standing height)."""
    sim = s2sim.Simulation(scene, defines=defines or {})
    gait = KeyPoseGait()
    inputs = [f"robots/humanoid/axes/{a}/ref_pos" for a in AXES]
    period_ticks = round(sim.control_period / sim.tick_s)
    trunk = "robots/humanoid/solids/trunk/"
    x0, z0 = sim.signal(trunk + "x"), sim.signal(trunk + "z")
    lowest = z0
    ticks = round(duration_s / sim.tick_s)
    for tick in range(ticks):
        # The script runs at the ticks that start at k·T - dt (k = 1, 2, ...), before the
        # servos: its goals act within that tick.
        if (tick + 1) % period_ticks == 0:
            sim.set_inputs(dict(zip(inputs, gait.goals())))
        sim.step(1)
        lowest = min(lowest, sim.signal(trunk + "z"))
        if on_tick:
            on_tick(sim)
    return sim.signal(trunk + "x") - x0, lowest / z0


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--duration", type=float, default=60.0, help="simulated seconds")
    args = parser.parse_args()
    distance, lowest = walk(args.duration)
    print(f"distance {distance:.4f} m, lowest trunk height {100 * lowest:.1f} % of standing")


if __name__ == "__main__":
    main()
