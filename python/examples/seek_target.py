#!/usr/bin/python3
"""The NXT drives to a red post on what its camera sees, without knowing where it or the post
is: python/examples/seek_target (scenes/nxt's robot with an 80 x 60 camera on its brick):

    PYTHONPATH=build/python /usr/bin/python3 python/examples/seek_target.py [--target 1.2 0.5]

At each camera frame (every 40 ms) the controller finds the red pixels of the colour image:
with none in sight it turns on the spot to look for them; otherwise it steers the centroid of
the red to the middle column and drives forward, slower as the post grows in the image, until
the post fills --fill of it; then it stops. The robot's pose (ground truth) is printed at the
end only, to see how close it came.
"""

import argparse
import os
import sys

import numpy as np

import s2sim

SCENE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "seek_target")
CAMERA = "robots/seeker/sensors/eye"
RIGHT, LEFT = "robots/seeker/axes/right/ref_voltage", "robots/seeker/axes/left/ref_voltage"
MAX_VOLTS = 9.0


def red_mask(rgb):
    """Pixels clearly red: lit or in shade (the post's sides are darker than its top)."""
    r, g, b = (rgb[..., i].astype(np.int16) for i in range(3))
    return (r > 50) & (r > 2 * g) & (r > 2 * b)


class Seeker:
    """Image in, wheel voltages out."""

    def __init__(self, fill=0.5, search_volts=2.5, drive_volts=6.0, steer_volts=4.0):
        self.fill, self.search_volts = fill, search_volts
        self.drive_volts, self.steer_volts = drive_volts, steer_volts
        self.done = False

    def __call__(self, rgb):
        mask = red_mask(rgb)
        seen = mask.sum() / mask.size
        if seen == 0:  # nothing red in sight: turn left on the spot to look (the left wheel
            # backward: a positive voltage, its motor facing the other way)
            return self.search_volts, self.search_volts
        width = rgb.shape[1]
        column = np.nonzero(mask)[1].mean()
        # Image column 0 is the left: a post right of the middle asks for a right turn.
        offset = (column - (width - 1) / 2) / (width / 2)  # -1 (left edge) .. 1 (right edge)
        if seen >= self.fill:
            self.done = True
        forward = 0.0 if self.done else self.drive_volts * min(1.0, 2 * (1 - seen / self.fill))
        forward *= max(0.0, 1 - 2 * abs(offset))  # turn first when the post is far off centre
        turn = -self.steer_volts * offset
        clamp = lambda v: max(-MAX_VOLTS, min(MAX_VOLTS, v))
        return clamp(forward + turn), -clamp(forward - turn)


def seek(target=(1.2, 0.5), duration_s=20.0, fill=0.5, seed=1):
    """Runs the seeker until it is done or duration_s has passed; returns the simulation."""
    sim = s2sim.Simulation(SCENE, seed=seed,
                           defines={"target_x": target[0], "target_y": target[1]})
    image = sim.image(CAMERA + "/rgb")  # a view: its pixels change at each frame
    frames = "robots/seeker/sensors/eye/frames"
    period_ticks = int(round(0.04 / sim.tick_s))
    controller = Seeker(fill=fill)
    sim.step(1)  # the camera's first frame
    while sim.time < duration_s and not controller.done:
        right, left = controller(image)
        sim.set_input(RIGHT, right)
        sim.set_input(LEFT, left)
        sim.step(period_ticks)
    sim.set_input(RIGHT, 0.0)
    sim.set_input(LEFT, 0.0)
    sim.step(int(round(0.5 / sim.tick_s)))  # come to rest
    assert sim.signal(frames) > 1
    return sim, controller.done


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--target", type=float, nargs=2, default=(1.2, 0.5), metavar=("X", "Y"))
    parser.add_argument("--fill", type=float, default=0.5,
                        help="stop when the post covers this fraction of the image")
    parser.add_argument("--duration", type=float, default=20.0)
    args = parser.parse_args()
    sim, done = seek(tuple(args.target), args.duration, args.fill)
    x, y = sim.signal("robots/seeker/x"), sim.signal("robots/seeker/y")
    distance = float(np.hypot(args.target[0] - x, args.target[1] - y))
    print("t = %.2f s: %s; robot at x = %.3f m, y = %.3f m; post at %.3f m"
          % (sim.time, "reached the post" if done else "gave up", x, y, distance))
    return 0 if done else 1


if __name__ == "__main__":
    sys.exit(main())
