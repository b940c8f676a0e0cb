#!/usr/bin/python3
"""Balances scenes/cartpole_remote from outside the simulation, through the remote protocol in
lock-step (docs/remote.md). Start the simulation, then this client:

    ./build/bin/s2sim-run scenes/cartpole_remote --duration 10 --define remote_port=9808 --log sim.csv &
    PYTHONPATH=build/python /usr/bin/python3 python/examples/cartpole_remote.py \
        --port 9808 --duration 10 --log client.csv

The controller is a discrete LQR designed here on the linearised cart-pole (the scene's masses
and pole length); its state is what the scene's `remote` controller serves: the cart's position
and speed, the pole's pitch (from vertical, positive leaning toward +x) and its pitch rate.
Only s2sim.remote (pure Python) and NumPy are used.
"""

import argparse
import sys

import numpy as np

from s2sim.remote import Client

CART_MASS_KG, POLE_MASS_KG, POLE_LENGTH_M, G = 1.0, 0.1, 1.0, 9.81
MAX_FORCE_N = 20.0


def lqr_gain(period_s):
    """K of u = -K s for s = (x, v, theta, omega), discrete LQR at the control period."""
    M, m, L = CART_MASS_KG, POLE_MASS_KG, POLE_LENGTH_M
    l, inertia = L / 2, m * L * L / 12
    # (M+m) a + m l alpha = F ; m l a + (I + m l^2) alpha = m g l theta
    mass = np.array([[M + m, m * l], [m * l, inertia + m * l * l]])
    inv = np.linalg.inv(mass)
    A = np.zeros((4, 4))
    A[0, 1] = A[2, 3] = 1
    A[[1, 3], 2] = inv @ np.array([0, m * G * l])
    B = np.zeros((4, 1))
    B[[1, 3], 0] = inv @ np.array([1, 0])
    # Zero-order hold: exp([[A, B], [0, 0]] h) by its series.
    n = np.zeros((5, 5))
    n[:4, :4], n[:4, 4:] = A * period_s, B * period_s
    e, term = np.eye(5), np.eye(5)
    for k in range(1, 30):
        term = term @ n / k
        e = e + term
    Ad, Bd = e[:4, :4], e[:4, 4:]
    Q, R = np.diag([1.0, 0.1, 10.0, 0.1]), np.array([[0.01]])
    P = Q.copy()
    for _ in range(5000):  # the discrete Riccati equation, iterated to its fixed point
        K = np.linalg.solve(R + Bd.T @ P @ Bd, Bd.T @ P @ Ad)
        P = Q + Ad.T @ P @ (Ad - Bd @ K)
    return K[0]


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--port", type=int, default=9808)
    parser.add_argument("--host", default="127.0.0.1")
    parser.add_argument("--duration", type=float, default=10.0, help="simulated seconds")
    parser.add_argument("--log", help="CSV of time, state and force per control period")
    args = parser.parse_args()

    with Client(port=args.port, host=args.host, timeout=30.0) as link:
        info = link.hello()
        if info.mode != "lockstep":
            sys.exit("the scene's remote controller is in %s mode, not lockstep" % info.mode)
        K = lqr_gain(info.period)
        steps = int(round(args.duration / info.period))
        log = open(args.log, "w") if args.log else None
        if log:
            log.write("time,x,v,pitch,pitch_rate,force\n")
        t, s = link.observe()
        for k in range(steps):
            force = float(np.clip(-K @ np.array(s), -MAX_FORCE_N, MAX_FORCE_N))
            if log:
                log.write("%.6f,%.17g,%.17g,%.17g,%.17g,%.17g\n" % (t, *s, force))
            if k == steps - 1:
                link.send([force])  # the last period: the simulation ends without replying
            else:
                t, s = link.step([force])
        if log:
            log.close()
        print("t = %.2f s: cart at %.4f m, pole at %.5f rad" % (t, s[0], s[2]))
        return 0 if abs(s[2]) < 0.05 and abs(s[0]) < 0.5 else 1


if __name__ == "__main__":
    sys.exit(main())
