#!/usr/bin/python3
"""The cart-pole balancing task as a gymnasium environment (s2sim.envs.CartPoleEnv: a
gymnasium.Env registered as "s2sim/CartPole-v0" where gymnasium is installed, a plain class
with the same API where it is not): a random policy and a hand-tuned linear one, five episodes
each.

    PYTHONPATH=build/python /usr/bin/python3 python/examples/cartpole_env.py

The task: scenes/cartpole, one action per 20 ms control period, a force on the cart in
[-10, 10] N; the observation is (cart x [m], cart speed [m/s], pole pitch [rad], pitch rate
[rad/s]); reward 1 per step while the pole is within 0.4 rad of vertical and the cart within
1.5 m; episodes are truncated after 500 steps (10 s).
"""

import os
import sys

import numpy as np

from s2sim.envs import CartPoleEnv

SCENE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scenes", "cartpole")


def episode(env, policy, seed):
    obs, _ = env.reset(seed=seed)
    total = 0.0
    while True:
        obs, reward, terminated, truncated, _ = env.step(policy(obs))
        total += reward
        if terminated or truncated:
            return total


def main():
    env = CartPoleEnv(SCENE)
    random_returns = [episode(env, lambda o: env.action_space.sample(), s) for s in range(5)]
    gains = np.array([-1.0, -2.0, -30.0, -6.0])  # u = -K s by hand: push under the pole
    linear_returns = [episode(env, lambda o: -gains @ o, s) for s in range(5)]
    print("random policy returns:", random_returns)
    print("linear policy returns:", linear_returns)
    return 0 if min(linear_returns) == env.max_steps and max(random_returns) < env.max_steps else 1


if __name__ == "__main__":
    sys.exit(main())
