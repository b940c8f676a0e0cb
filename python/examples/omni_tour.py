#!/usr/bin/python3
"""Drives scenes/firefighting_omni through the four rooms of the Fire-Fighting arena from
outside the simulation, localising the robot with a particle filter on its wheel odometry and
its six noisy IR distances against the known walls (docs/tutorials/omni-localisation.md).
Start the simulation, then this client:

    ./build/bin/s2sim-run scenes/firefighting_omni --duration 60 --define remote_port=9809 &
    PYTHONPATH=build/python /usr/bin/python3 python/examples/omni_tour.py \
        --port 9809 --log tour.csv

Everything the filter knows comes from the scene's files, read here: the walls (arena.xml),
the start pose (scene.xml), the wheels, encoders and IR sensors with their noise model
(omni_ir.xml). Every control period (lock-step) it receives the IR distances and the encoder
counts, moves its particles by the odometry with noise, weighs them by the IR ranges cast
against the walls, resamples, and sends the wheels' speed references that take the estimate
to the next waypoint. The robot's true pose, also served, is only written to the log. Only
s2sim.remote (pure Python) and NumPy are used; the same --seed gives the same run.
"""

import argparse
import math
import os
import sys
import xml.etree.ElementTree as ET

import numpy as np

from s2sim.remote import Client, RunEnded

SCENE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scenes",
                     "firefighting_omni")
ROBOT = "robots/omni/"

# The tour: hallway waypoints the robot passes, and one goal inside each room (its name), along
# the hallways' centre lines (46 cm wide: 11 cm on either side of the robot's wheels).
TOUR = [
    (1.29, 1.03, None), (2.13, 1.03, None), (2.13, 0.45, "room4"), (2.13, 1.03, None),
    (1.29, 1.03, None), (1.22, 1.29, None), (1.15, 1.55, None), (1.15, 2.03, None),
    (1.80, 2.03, "room2"), (1.15, 2.03, None), (1.15, 1.55, None), (1.15, 1.29, None),
    (0.53, 1.29, None), (0.53, 2.00, "room1"), (0.53, 1.29, None), (1.22, 1.29, None),
    (1.29, 1.03, None), (1.29, 0.53, None), (0.55, 0.53, "room3"),
]
ROOMS = [room for _, _, room in TOUR if room]

SPEED_M_S = 0.30          # cruising speed
ACCEL_M_S2 = 0.6          # speed change per second, to keep the omni rollers from slipping
PASS_RADIUS_M = 0.06      # a hallway waypoint is passed within this
GOAL_RADIUS_M = 0.03      # a room's goal is reached within this
HEADING_GAIN = 2.0        # 1/s, holds the start heading


def number(element, name, default=None):
    value = element.get(name)
    if value is None:
        if default is None:
            raise ValueError("%s: no %s" % (element.tag, name))
        return default
    return float(value)


class Model:
    """What the client knows of the robot and the arena, read from the scene's files."""

    def __init__(self, scene_dir):
        scene = ET.parse(os.path.join(scene_dir, "scene.xml")).getroot()
        robot = scene.find("robot")
        pos, rot = robot.find("pos"), robot.find("rot_deg")
        self.start = np.array([number(pos, "x"), number(pos, "y"),
                               math.radians(number(rot, "z", 0.0) if rot is not None else 0.0)])
        arena = ET.parse(os.path.join(scene_dir, scene.find("obstacles").get("file"))).getroot()
        # The walls are boxes aligned with the axes: their faces are lines x = c (for y in
        # [lo, hi]) and y = c (for x in [lo, hi]), which a ray meets in a few operations.
        across_x, across_y = [], []  # (c, lo, hi)
        for box in arena.iter("cuboid"):
            rot = box.find("rot_deg")
            if rot is not None and any(number(rot, a, 0.0) for a in "xyz"):
                raise ValueError("%s: a rotated wall; the map takes boxes aligned with the axes"
                                 % box.find("ID").get("value"))
            size, centre = box.find("size"), box.find("pos")
            hx, hy = number(size, "x") / 2, number(size, "y") / 2
            cx, cy = number(centre, "x"), number(centre, "y")
            across_x += [(cx - hx, cy - hy, cy + hy), (cx + hx, cy - hy, cy + hy)]
            across_y += [(cy - hy, cx - hx, cx + hx), (cy + hy, cx - hx, cx + hx)]
        self.faces_x, self.faces_y = np.array(across_x), np.array(across_y)

        body = ET.parse(os.path.join(scene_dir, robot.find("body").get("file"))).getroot()
        default = body.find("wheels/default")
        tyre = default.find("tyre")
        self.wheel_radius_m = number(tyre, "radius")
        self.centre_distance_m = number(tyre, "centerdist")
        self.ppr = number(default.find("encoder"), "ppr")
        self.wheels = [w.find("ID").get("value") for w in body.findall("wheels/wheel")]
        angles = [math.radians(number(w.find("axis"), "angle")) for w in body.findall("wheels/wheel")]
        # A wheel's rim speed for a body velocity (vx, vy, w) in the robot frame.
        self.kinematics = np.array([[-math.sin(a), math.cos(a), self.centre_distance_m]
                                    for a in angles])
        self.inverse_kinematics = np.linalg.inv(self.kinematics)

        self.sensors, mounts = [], []
        for ir in body.iter("IRSharp"):
            p, r, beam, noise = ir.find("pos"), ir.find("rot_deg"), ir.find("beam"), ir.find("noise")
            self.sensors.append(ir.find("ID").get("value"))
            mounts.append((number(p, "x"), number(p, "y"), math.radians(number(r, "z", 0.0))))
            self.beam_m = number(beam, "length")
            self.noise = {k: number(noise, k, 0.0) for k in ("gain", "offset", "var_k", "var_d")}
        self.mounts = np.array(mounts)  # (K, 3): x, y in the body frame, beam direction

    def sigma_m(self, d):
        """The IR reading's standard deviation at distance d (docs/models/sensors.md, IRSharp)."""
        n = self.noise
        return np.sqrt(n["var_d"] * d + n["var_k"]) * (n["gain"] * d + n["offset"]) ** 2 / abs(n["gain"])

    def ranges(self, poses):
        """(N, K) distances from each pose's K sensors to the nearest wall, inf past the walls."""
        c, s = np.cos(poses[:, 2:3]), np.sin(poses[:, 2:3])
        mx, my, ma = self.mounts[:, 0], self.mounts[:, 1], self.mounts[:, 2]
        ox = (poses[:, 0:1] + c * mx - s * my).reshape(-1, 1)
        oy = (poses[:, 1:2] + s * mx + c * my).reshape(-1, 1)
        heading = (poses[:, 2:3] + ma).reshape(-1, 1)
        dx, dy = np.cos(heading), np.sin(heading)
        with np.errstate(divide="ignore", invalid="ignore"):
            nearest = np.full(ox.shape[0], np.inf)
            for (o, d, p, q), faces in (((ox, dx, oy, dy), self.faces_x),
                                        ((oy, dy, ox, dx), self.faces_y)):
                t = (faces[:, 0] - o) / d          # (N*K, F): along the ray to the face's line
                along = p + t * q                  # where on the line
                hit = (t > 0) & (along >= faces[:, 1]) & (along <= faces[:, 2])
                nearest = np.minimum(nearest, np.where(hit, t, np.inf).min(axis=1))
        return nearest.reshape(poses.shape[0], -1)


class ParticleFilter:
    def __init__(self, model, start, count, rng):
        self.model, self.rng = model, rng
        self.particles = np.tile(start, (count, 1)) + rng.normal(0, 1, (count, 3)) * [0.01, 0.01, 0.01]
        self.weights = np.full(count, 1.0 / count)

    def predict(self, rim_m):
        """Moves every particle by the wheels' rim travel, each wheel's with its own noise
        (slip grows with the travel)."""
        n = len(self.particles)
        sigma = 0.04 * np.abs(rim_m) + 2e-4
        noisy = rim_m + self.rng.normal(0, 1, (n, 3)) * sigma
        body = noisy @ self.model.inverse_kinematics.T  # (N, 3): dx, dy, dtheta in the body frame
        heading = self.particles[:, 2] + body[:, 2] / 2
        c, s = np.cos(heading), np.sin(heading)
        self.particles[:, 0] += c * body[:, 0] - s * body[:, 1]
        self.particles[:, 1] += s * body[:, 0] + c * body[:, 1]
        self.particles[:, 2] += body[:, 2]

    def update(self, readings):
        """Weighs the particles by the IR readings (−1: nothing within the beam)."""
        m = self.model
        predicted = m.ranges(self.particles)
        log_weight = np.zeros(len(self.particles))
        for k, z in enumerate(readings):
            d = predicted[:, k]
            inside = d < m.beam_m
            if z < 0:
                likelihood = np.where(inside, 0.05, 1.0)
            else:
                # The sensor's own spread, plus 3 mm for what the model leaves out.
                sigma = np.sqrt(m.sigma_m(np.minimum(d, m.beam_m)) ** 2 + 0.003 ** 2)
                gauss = np.exp(-0.5 * ((z - d) / sigma) ** 2) / sigma
                likelihood = np.where(inside, gauss, 0.0) + 0.05 / m.beam_m  # outliers
            log_weight += np.log(likelihood)
        w = self.weights * np.exp(log_weight - log_weight.max())
        self.weights = w / w.sum()
        if 1.0 / np.sum(self.weights ** 2) < len(self.weights) / 2:
            self.resample()

    def resample(self):
        """Systematic resampling."""
        n = len(self.weights)
        positions = (self.rng.random() + np.arange(n)) / n
        index = np.minimum(np.searchsorted(np.cumsum(self.weights), positions), n - 1)
        self.particles = self.particles[index]
        self.weights = np.full(n, 1.0 / n)

    def estimate(self):
        w = self.weights
        yaw = math.atan2(np.sum(w * np.sin(self.particles[:, 2])), np.sum(w * np.cos(self.particles[:, 2])))
        return np.array([np.sum(w * self.particles[:, 0]), np.sum(w * self.particles[:, 1]), yaw])

    def spread(self):
        """The particles' weighted standard deviations in x, y (m) and yaw (rad)."""
        w, mean = self.weights, self.estimate()
        offsets = self.particles - mean
        offsets[:, 2] = (offsets[:, 2] + math.pi) % (2 * math.pi) - math.pi
        return np.sqrt(w @ offsets ** 2)


def wrap(angle):
    return (angle + math.pi) % (2 * math.pi) - math.pi


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--port", type=int, default=9809)
    parser.add_argument("--host", default="127.0.0.1")
    parser.add_argument("--scene", default=SCENE, help="the scene folder (its files are the map)")
    parser.add_argument("--particles", type=int, default=300)
    parser.add_argument("--seed", type=int, default=1, help="seed of the filter's random numbers")
    parser.add_argument("--log", help="CSV of the estimate, the true pose and the dead reckoning")
    args = parser.parse_args()

    model = Model(args.scene)
    rng = np.random.default_rng(args.seed)
    pf = ParticleFilter(model, model.start, args.particles, rng)
    dead_reckoning = model.start.copy()

    with Client(port=args.port, host=args.host, timeout=30.0) as link:
        info = link.hello()
        if info.mode != "lockstep":
            sys.exit("the scene's remote controller is in %s mode, not lockstep" % info.mode)
        where = {name: k for k, name in enumerate(info.signals)}
        ir = [where[ROBOT + "sensors/%s/value" % s] for s in model.sensors]
        encoders = [where[ROBOT + "axes/%s/encoder" % w] for w in model.wheels]
        truth = [where[ROBOT + q] for q in ("x", "y", "yaw")]
        inputs = {ROBOT + "axes/%s/ref_speed" % w: k for k, w in enumerate(model.wheels)}
        order = [inputs[name] for name in info.inputs]
        log = open(args.log, "w") if args.log else None
        if log:
            log.write("time,est_x,est_y,est_yaw,sd_x,sd_y,sd_yaw,true_x,true_y,true_yaw,"
                      "odo_x,odo_y,odo_yaw,waypoint,touring\n")

        t, y = link.observe()
        counts = np.array([y[k] for k in encoders])
        target, speed, arrivals, squared, samples = 0, 0.0, {}, 0.0, 0
        try:
            while True:
                now = np.array([y[k] for k in encoders])
                rim_m = (now - counts) * 2 * math.pi / model.ppr * model.wheel_radius_m
                counts = now
                pf.predict(rim_m)
                body = model.inverse_kinematics @ rim_m
                heading = dead_reckoning[2] + body[2] / 2
                dead_reckoning += [math.cos(heading) * body[0] - math.sin(heading) * body[1],
                                   math.sin(heading) * body[0] + math.cos(heading) * body[1], body[2]]
                pf.update([y[k] for k in ir])
                est = pf.estimate()
                true = np.array([y[k] for k in truth])
                touring = target < len(TOUR)
                if touring:
                    squared += (est[0] - true[0]) ** 2 + (est[1] - true[1]) ** 2
                    samples += 1
                if log:
                    log.write("%.6f,%s,%d,%d\n" % (t, ",".join("%.17g" % v for v in
                              (*est, *pf.spread(), *true, *dead_reckoning)), target, touring))

                wheels = np.zeros(3)
                if touring:
                    gx, gy, room = TOUR[target]
                    error = np.array([gx - est[0], gy - est[1]])
                    distance = float(np.hypot(*error))
                    if distance < (GOAL_RADIUS_M if room else PASS_RADIUS_M):
                        if room:
                            arrivals[room] = t
                            print("%s reached at t = %.2f s: estimate (%.3f, %.3f), true (%.3f, %.3f)"
                                  % (room, t, est[0], est[1], true[0], true[1]), flush=True)
                            speed = 0.0
                        target += 1
                    else:
                        # Slow down into a room's goal (and on the last stretch), not at a
                        # waypoint passed on the way.
                        wanted = SPEED_M_S if not room else min(SPEED_M_S, 1.5 * distance)
                        speed = min(wanted, speed + ACCEL_M_S2 * info.period)
                        vx, vy = error / distance * speed
                        c, s = math.cos(est[2]), math.sin(est[2])
                        w = -HEADING_GAIN * wrap(est[2] - model.start[2])
                        wheels = model.kinematics @ [c * vx + s * vy, -s * vx + c * vy, w]
                        wheels /= model.wheel_radius_m
                t, y = link.step([float(wheels[k]) for k in order])
        except RunEnded:
            pass
        if log:
            log.close()
    rms = math.sqrt(squared / max(samples, 1))
    print("tour %s: %d of %d rooms, position error %.4f m RMS over %d periods"
          % ("done" if len(arrivals) == len(ROOMS) else "NOT done", len(arrivals), len(ROOMS), rms,
             samples))
    return 0 if len(arrivals) == len(ROOMS) else 1


if __name__ == "__main__":
    sys.exit(main())
