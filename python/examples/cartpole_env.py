#!/usr/bin/python3
"""A gymnasium-style environment over the bindings, without depending on gymnasium: the API is
the same (reset(seed) -> (obs, info); step(action) -> (obs, reward, terminated, truncated,
info)), so a learning loop written for gymnasium runs on it unchanged, and
gymnasium.Env can be added as a base class where gymnasium is installed.

    PYTHONPATH=build/python /usr/bin/python3 python/examples/cartpole_env.py

The task: scenes/cartpole, one action per 20 ms control period, a force on the cart in
[-10, 10] N; the observation is (cart x [m], cart speed [m/s], pole pitch [rad], pitch rate
[rad/s]); reward 1 per step while the pole is within 0.4 rad of vertical and the cart within
1.5 m; episodes are truncated after 500 steps (10 s).
"""

import os
import sys

import numpy as np

import s2sim

SCENE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scenes", "cartpole")
FORCE = "robots/cartpole/axes/slide/ref_torque"
OBSERVED = ["robots/cartpole/axes/slide/pos", "robots/cartpole/axes/slide/speed",
            "robots/cartpole/solids/pole/pitch", "robots/cartpole/solids/pole/wy"]


class Box:
    """gymnasium.spaces.Box's essentials: bounds, shape, sample()."""

    def __init__(self, low, high, rng=None):
        self.low, self.high = np.asarray(low, dtype=float), np.asarray(high, dtype=float)
        self.shape = self.low.shape
        self.rng = rng or np.random.default_rng()

    def sample(self):
        return self.rng.uniform(self.low, self.high)

    def contains(self, x):
        x = np.asarray(x)
        return x.shape == self.shape and bool(np.all(x >= self.low) and np.all(x <= self.high))


class CartPoleEnv:
    max_force_N = 10.0
    max_steps = 500
    pole_limit_rad, cart_limit_m = 0.4, 1.5

    def __init__(self, scene=SCENE, tilt_deg=0.0):
        # tilt_deg 0: the pole starts upright; reset() gives it a random push.
        self.sim = s2sim.Simulation(scene, defines={"tilt_deg": tilt_deg})
        self.period_ticks = int(round(self.sim.control_period / self.sim.tick_s))
        self.action_space = Box([-self.max_force_N], [self.max_force_N])
        inf = np.inf
        self.observation_space = Box([-inf] * 4, [inf] * 4)
        self.rng = np.random.default_rng()
        self.steps = 0

    def _observe(self):
        return self.sim.signals(OBSERVED)  # one call, in OBSERVED's order

    def reset(self, seed=None, options=None):
        if seed is not None:
            self.rng = np.random.default_rng(seed)
            self.action_space.rng = np.random.default_rng(seed + 1)
        self.sim.reset()
        push = self.rng.uniform(-2.0, 2.0)  # N for 0.1 s: a random start near upright
        self.sim.set_input(FORCE, push)
        self.sim.step(5 * self.period_ticks)
        self.sim.set_input(FORCE, 0.0)
        self.steps = 0
        return self._observe(), {"push_N": push, "time": self.sim.time}

    def step(self, action):
        force = float(np.clip(np.asarray(action, dtype=float).reshape(-1)[0],
                              -self.max_force_N, self.max_force_N))
        self.sim.set_input(FORCE, force)
        self.sim.step(self.period_ticks)  # the GIL is released meanwhile
        self.steps += 1
        obs = self._observe()
        terminated = bool(abs(obs[2]) > self.pole_limit_rad or abs(obs[0]) > self.cart_limit_m)
        truncated = self.steps >= self.max_steps
        return obs, (0.0 if terminated else 1.0), terminated, truncated, {"time": self.sim.time}

    def close(self):
        self.sim = None


def episode(env, policy, seed):
    obs, _ = env.reset(seed=seed)
    total = 0.0
    while True:
        obs, reward, terminated, truncated, _ = env.step(policy(obs))
        total += reward
        if terminated or truncated:
            return total


def main():
    env = CartPoleEnv()
    random_returns = [episode(env, lambda o: env.action_space.sample(), s) for s in range(5)]
    gains = np.array([-1.0, -2.0, -30.0, -6.0])  # u = -K s by hand: push under the pole
    linear_returns = [episode(env, lambda o: -gains @ o, s) for s in range(5)]
    print("random policy returns:", random_returns)
    print("linear policy returns:", linear_returns)
    return 0 if min(linear_returns) == env.max_steps and max(random_returns) < env.max_steps else 1


if __name__ == "__main__":
    sys.exit(main())
