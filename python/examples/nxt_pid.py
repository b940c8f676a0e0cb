#!/usr/bin/python3
"""A PID in Python drives scenes/nxt through the bindings: to a point 0.5 m ahead and stops
there, keeping its heading. The loop runs every 10 ms of simulated time:

    PYTHONPATH=build/python /usr/bin/python3 python/examples/nxt_pid.py [--target 0.5]

Forward is +x; the right wheel turns forward with a positive voltage, the left one with a
negative voltage (the motors face each other).
"""

import argparse
import os
import sys

import s2sim

SCENE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scenes", "nxt")
RIGHT, LEFT = "robots/nxt/axes/right/ref_voltage", "robots/nxt/axes/left/ref_voltage"
MAX_VOLTS = 9.0


class Pid:
    def __init__(self, kp, ki, kd, period_s):
        self.kp, self.ki, self.kd, self.period_s = kp, ki, kd, period_s
        self.integral, self.previous = 0.0, None

    def __call__(self, error):
        self.integral += error * self.period_s
        derivative = 0.0 if self.previous is None else (error - self.previous) / self.period_s
        self.previous = error
        return self.kp * error + self.ki * self.integral + self.kd * derivative


def clamp(v, limit):
    return max(-limit, min(limit, v))


def drive_to(target_m, duration_s=4.0, period_s=0.01, seed=1, log=None):
    sim = s2sim.Simulation(SCENE, seed=seed)
    ticks = int(round(period_s / sim.tick_s))
    distance = Pid(60.0, 0.0, 10.0, period_s)  # volts per metre of error: a PD (the motors
    # saturate for most of the way, where an integral would only wind up)
    heading = Pid(20.0, 0.0, 0.5, period_s)   # volts per radian of yaw
    while sim.time < duration_s - 1e-9:
        x, yaw = sim.signal("robots/nxt/x"), sim.signal("robots/nxt/yaw")
        forward = clamp(distance(target_m - x), MAX_VOLTS)
        turn = clamp(heading(-yaw), MAX_VOLTS / 2)
        sim.set_input(RIGHT, clamp(forward + turn, MAX_VOLTS))
        sim.set_input(LEFT, -clamp(forward - turn, MAX_VOLTS))
        if log:
            log.write("%.3f,%.6f,%.6f,%.3f\n" % (sim.time, x, yaw, forward))
        sim.step(ticks)
    return sim


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--target", type=float, default=0.5, help="metres ahead")
    parser.add_argument("--duration", type=float, default=4.0)
    args = parser.parse_args()
    sim = drive_to(args.target, args.duration)
    x, y, yaw = (sim.signal("robots/nxt/" + n) for n in ("x", "y", "yaw"))
    speed = sim.signal("robots/nxt/vx")
    print("t = %.2f s: x = %.4f m (target %.3f), y = %.4f m, yaw = %.4f rad, vx = %.4f m/s"
          % (sim.time, x, args.target, y, yaw, speed))
    return 0 if abs(x - args.target) < 0.01 and abs(speed) < 0.01 else 1


if __name__ == "__main__":
    sys.exit(main())
